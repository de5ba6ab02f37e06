#include "segments.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"

#include <algorithm>
#include <string>
#include <vector>

namespace iarap::detail {

Eigen::VectorXi segment_offsets(const CompactTraces& traces, int num_edges) {
  Eigen::VectorXi start(num_edges + 1);
  start(0) = 0;
  for (int e = 0; e < num_edges; ++e) {
    const int k = traces.job[static_cast<size_t>(e)];
    start(e + 1) =
        start(e) +
        (k < 0 ? 1 : traces.start[static_cast<size_t>(k) + 1] - traces.start[static_cast<size_t>(k)] - 1);
  }
  return start;
}

namespace {

// s_hat = V^T b summed in slot order, and its length.
void set_rest_vector(const RowPositions& V, SegmentVector& out) {
  out.s_hat.setZero();
  for (int q = 0; q < 3; ++q) out.s_hat += out.value[q] * V.row(out.index[q]).transpose();
  out.length = out.s_hat.norm();
}

} // namespace

bool segment_vector(const RowPositions& V, const TracePoint& p0, const TracePoint& p1, SegmentVector& out) {
  if (p0.c < 0 && p1.c < 0 && p0.a != p1.a) {
    // Vertex to vertex (every edge never flipped): what the merge below gives, without its searches.
    out.index[0] = out.index[2] = p1.a;
    out.index[1] = p0.a;
    out.value[0] = 1.0;
    out.value[1] = -1.0;
    out.value[2] = 0.0;
    set_rest_vector(V, out);
    out.face = p0.face;
    return true;
  }
  int n = 0;
  auto add = [&](int v, double coefficient) {
    for (int q = 0; q < n; ++q)
      if (out.index[q] == v) {
        out.value[q] += coefficient;
        return true;
      }
    if (n == 3) return false;
    out.index[n] = v;
    out.value[n++] = coefficient;
    return true;
  };
  // b = b(end point) - b(start point); a point is (1 - t) e_a + t e_c, or e_a alone.
  bool ok = p1.c < 0 ? add(p1.a, 1.0) : add(p1.a, 1.0 - p1.t) && add(p1.c, p1.t);
  ok = ok && (p0.c < 0 ? add(p0.a, -1.0) : add(p0.a, -(1.0 - p0.t)) && add(p0.c, -p0.t));
  if (!ok) return false;
  for (int q = n; q < 3; ++q) {
    out.index[q] = out.index[0];
    out.value[q] = 0.0;
  }
  set_rest_vector(V, out);
  out.face = p0.face;
  return true;
}

void throw_segment_error(int segment) {
  throw SolverError("segment " + std::to_string(segment) +
                    " has end points on no common input face (more than 3 vertices in b)");
}

Segments build_segments(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri,
                        const CompactTraces& traces, bool assemble_B) {
  const int ne = static_cast<int>(tri.E.rows());
  Segments seg;
  seg.edge_start = segment_offsets(traces, ne);
  const int ns = seg.edge_start(ne);
  seg.edge.resize(ns);
  seg.face.resize(ns);
  seg.b_index.resize(ns, 3);
  seg.b_value.resize(ns, 3);
  seg.s_hat.resize(ns, 3);
  seg.length.resize(ns);
  seg.weight.resize(ns);
  for_each_segment(V, tri, traces, seg.edge_start, [&](int s, int e, const SegmentVector& segment) {
    for (int q = 0; q < 3; ++q) {
      seg.b_index(s, q) = segment.index[q];
      seg.b_value(s, q) = segment.value[q];
    }
    seg.edge(s) = e;
    seg.face(s) = segment.face;
    seg.s_hat.row(s) = segment.s_hat.transpose();
    seg.length(s) = segment.length;
    seg.weight(s) = segment.weight;
  });
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
