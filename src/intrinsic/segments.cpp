#include "segments.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"

#include <algorithm>
#include <string>
#include <vector>

namespace iarap::detail {

Segments build_segments(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri, const CompactTraces& traces,
                        bool assemble_B) {
  const int ne = static_cast<int>(tri.E.rows());
  Segments seg;
  seg.edge_start.resize(ne + 1);
  seg.edge_start(0) = 0;
  for (int e = 0; e < ne; ++e) {
    const int k = traces.job[static_cast<size_t>(e)];
    seg.edge_start(e + 1) = seg.edge_start(e) + (k < 0 ? 1 : traces.start[static_cast<size_t>(k) + 1] - traces.start[static_cast<size_t>(k)] - 1);
  }
  const int ns = seg.edge_start(ne);
  seg.edge.resize(ns);
  seg.face.resize(ns);
  seg.b_index.resize(ns, 3);
  seg.b_value.resize(ns, 3);
  seg.s_hat.resize(ns, 3);
  seg.length.resize(ns);
  seg.weight.resize(ns);
  bool bad = false;
  int bad_segment = -1;

#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int e = 0; e < ne; ++e) {
    const double w = tri.cot_weight(e), l = tri.length(e);
    TracePoint ends[2];
    int count = 0;
    const TracePoint* points = traces.edge_points(e, tri.E, ends, count);
    for (int m = 0; m + 1 < count; ++m) {
      const int s = seg.edge_start(e) + m;
      int idx[3];
      double val[3] = {0, 0, 0};
      int n = 0;
      auto add = [&](int v, double coefficient) {
        for (int q = 0; q < n; ++q)
          if (idx[q] == v) {
            val[q] += coefficient;
            return true;
          }
        if (n == 3) return false;
        idx[n] = v;
        val[n++] = coefficient;
        return true;
      };
      const TracePoint &p0 = points[m], &p1 = points[m + 1];
      bool ok = true;
      // b = b(end point) - b(start point); a point is (1 - t) e_a + t e_c, or e_a alone.
      if (p1.c < 0) ok &= add(p1.a, 1.0);
      else ok &= add(p1.a, 1.0 - p1.t) && add(p1.c, p1.t);
      if (p0.c < 0) ok &= add(p0.a, -1.0);
      else ok &= add(p0.a, -(1.0 - p0.t)) && add(p0.c, -p0.t);
      if (!ok) {
#pragma omp critical
        {
          bad = true;
          bad_segment = s;
        }
        continue;
      }
      for (int q = n; q < 3; ++q) {
        idx[q] = idx[0];
        val[q] = 0.0;
      }
      Eigen::Vector3d s_hat = Eigen::Vector3d::Zero();
      for (int q = 0; q < 3; ++q) {
        seg.b_index(s, q) = idx[q];
        seg.b_value(s, q) = val[q];
        s_hat += val[q] * V.row(idx[q]).transpose();
      }
      const double len = s_hat.norm();
      seg.edge(s) = e;
      seg.face(s) = p0.face;
      seg.s_hat.row(s) = s_hat.transpose();
      seg.length(s) = len;
      seg.weight(s) = len > 1e-12 * l ? w * l / len : 0.0; // Eq. 11: w_ij^t = sigma_ij^t w_ij, sigma = |e| / |s|
    }
  }
  if (bad)
    throw SolverError("segment " + std::to_string(bad_segment) +
                      " has end points on no common input face (more than 3 vertices in b)");
  if (!assemble_B) return seg;

  // B in compressed column form directly (a counting sort by vertex): segments are visited in order, so
  // each column's rows come out sorted, with none of setFromTriplets' sort and temporary copies.
  const int nv = static_cast<int>(V.rows());
  seg.B.resize(ns, nv);
  std::vector<int> fill(static_cast<size_t>(nv) + 1, 0);
  for (int s = 0; s < ns; ++s)
    for (int q = 0; q < 3; ++q)
      if (seg.b_value(s, q) != 0.0) ++fill[static_cast<size_t>(seg.b_index(s, q)) + 1];
  for (int v = 0; v < nv; ++v) fill[static_cast<size_t>(v) + 1] += fill[static_cast<size_t>(v)];
  seg.B.resizeNonZeros(fill[static_cast<size_t>(nv)]);
  std::copy(fill.begin(), fill.end(), seg.B.outerIndexPtr());
  for (int s = 0; s < ns; ++s)
    for (int q = 0; q < 3; ++q)
      if (seg.b_value(s, q) != 0.0) {
        const int k = fill[static_cast<size_t>(seg.b_index(s, q))]++;
        seg.B.innerIndexPtr()[k] = s;
        seg.B.valuePtr()[k] = seg.b_value(s, q);
      }
  return seg;
}

} // namespace iarap::detail
