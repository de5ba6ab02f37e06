#include "iarap/mesh/edge_topology.h"

#include "iarap/core/threads.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace iarap {

namespace {

struct Corner {
  int other;       // the larger vertex of the opposite edge
  int face_corner; // 3 f + k
};

// Buckets up to this size take the insertion sort: fewer moves than a merge sort at valence 6, and no
// buffer. Beyond it std::stable_sort keeps the worst case at O(k log k).
constexpr std::ptrdiff_t insertion_sort_limit = 32;

// Stable sort of [first, last) by `other`.
void sort_bucket(Corner* first, Corner* last) {
  const auto by_other = [](const Corner& a, const Corner& b) { return a.other < b.other; };
  if (last - first > insertion_sort_limit) {
    std::stable_sort(first, last, by_other);
    return;
  }
  for (Corner* i = first; i < last; ++i) {
    const Corner c = *i;
    Corner* j = i;
    for (; j > first && (j - 1)->other > c.other; --j) *j = *(j - 1);
    *j = c;
  }
}

} // namespace

EdgeTopology edge_topology(const Eigen::MatrixXi& F, int num_vertices) {
  const int nf = static_cast<int>(F.rows());
  const size_t nv = static_cast<size_t>(num_vertices);
  // Bucket every face corner by the smaller vertex of its opposite edge (counting sort, linear time),
  // then order each bucket by the larger vertex. Faces are visited in order and both sorts are stable, so
  // equal edges keep their (face, corner) order: the same result as sorting all corners by (min vertex,
  // max vertex, face, corner). Small buckets (the usual valence) take an insertion sort; a large one (a
  // vertex of valence 200K, a fan-triangulated polygon of a million corners) a merge sort, so that a
  // bucket given in decreasing order costs O(k log k), not O(k^2).
  std::vector<int> start(nv + 1, 0);
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      ++start[static_cast<size_t>(a < b ? a : b) + 1];
    }
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<Corner> bucket(static_cast<size_t>(3 * nf));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
        const int lo = a < b ? a : b, hi = a < b ? b : a;
        bucket[static_cast<size_t>(fill[static_cast<size_t>(lo)]++)] = {hi, 3 * f + k};
      }
  }
  // Sort each bucket and count its distinct edges (vertices are independent: parallel), then number the
  // edges by a prefix sum over vertices and fill the incidences, again per vertex.
  const int nvi = num_vertices;
  std::vector<int> edge_start(nv + 1, 0);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(dynamic, 4096)
  for (int v = 0; v < nvi; ++v) {
    const int first = start[static_cast<size_t>(v)], last = start[static_cast<size_t>(v) + 1];
    int distinct = 0;
    sort_bucket(bucket.data() + first, bucket.data() + last);
    for (int i = first; i < last; ++i)
      distinct +=
          i == first || bucket[static_cast<size_t>(i)].other != bucket[static_cast<size_t>(i - 1)].other;
    edge_start[static_cast<size_t>(v) + 1] = distinct;
  }
  for (size_t v = 0; v < nv; ++v) edge_start[v + 1] += edge_start[v];
  const int ne = edge_start[nv];

  EdgeTopology t;
  t.E.resize(ne, 2);
  t.EF.setConstant(ne, 2, -1);
  t.EK.setConstant(ne, 2, -1);
  t.face_count.setZero(ne);
  t.FE.resize(nf, 3);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(dynamic, 4096)
  for (int v = 0; v < nvi; ++v) {
    const int first = start[static_cast<size_t>(v)], last = start[static_cast<size_t>(v) + 1];
    int e = edge_start[static_cast<size_t>(v)] - 1;
    for (int i = first; i < last; ++i) {
      const Corner c = bucket[static_cast<size_t>(i)];
      if (i == first || c.other != bucket[static_cast<size_t>(i - 1)].other) {
        ++e;
        t.E(e, 0) = v;
        t.E(e, 1) = c.other;
      }
      const int f = c.face_corner / 3, k = c.face_corner % 3;
      const int slot = t.face_count(e)++;
      if (slot < 2) {
        t.EF(e, slot) = f;
        t.EK(e, slot) = k;
      }
      t.FE(f, k) = e;
    }
  }
  return t;
}

} // namespace iarap
