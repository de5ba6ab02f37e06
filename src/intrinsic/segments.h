// Internal: cuts traced intrinsic edges into segments s = V b (Eq. 7-8) with weights (Eq. 11).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "trace_edges.h"

#include "iarap/core/threads.h"

#include <algorithm>

namespace iarap::detail {

// Segment m of edge e runs from trace point m to m + 1. Its b merges the barycentric vectors of the two
// points (each an input vertex or a point on an input edge of the carrying face), so it has at most three
// non-zeros that sum to 0. weight = cot_weight(e) * length(e) / |s| (Eq. 11); a segment shorter than
// 1e-12 |e| (a trace grazing a vertex) gets weight 0, since its b b^T / |s| term would be unbounded.
// B is assembled only when asked.
Segments build_segments(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri,
                        const CompactTraces& traces, bool assemble_B);

// The segments of every intrinsic edge as offsets: edge e owns segments start[e] .. start[e + 1).
Eigen::VectorXi segment_offsets(const CompactTraces& traces, int num_edges);

// One segment s = V^T b from trace point p0 to p1 (Eq. 7-8).
struct SegmentVector {
  int index[3];          // distinct vertices of b; an unused slot repeats index[0] with value 0
  double value[3];       // coefficients, summing to 0 (one may cancel to 0)
  Eigen::Vector3d s_hat; // V^T b, summed in slot order
  double length;         // |s_hat|
  double weight;         // Eq. 11 (set by for_each_segment)
  int face;              // the input face carrying the segment
};

// V with each vertex's coordinates side by side: a segment's rest vector reads its (up to 3) vertices in
// one cache line each, not three (a column-major V), in the order of the traces, which is not the file's.
using RowPositions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// b, s_hat and length of the segment from p0 to p1; false when the points share no input face (b would
// have more than three vertices).
bool segment_vector(const RowPositions& V, const TracePoint& p0, const TracePoint& p1, SegmentVector& out);

// The segment's weight w_ij^t = sigma_ij^t w_ij with sigma = |e_ij| / |s| (Eq. 11), 0 for a grazing segment.
inline double segment_weight(double edge_cot_weight, double edge_length, double segment_length) {
  return segment_length > 1e-12 * edge_length ? edge_cot_weight * edge_length / segment_length : 0.0;
}

// The SolverError for a segment whose end points share no input face.
[[noreturn]] void throw_segment_error(int segment);

// Calls visit(s, e, segment) for every segment s of every intrinsic edge e (start: segment_offsets), in
// parallel over edges; then throws SolverError naming the first segment whose end points share no face.
// The one walk over the traces behind build_segments and the solver's traced_iarap_elements.
template <class Visit>
void for_each_segment(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri,
                      const CompactTraces& traces, const Eigen::VectorXi& start, const Visit& visit) {
  const int ne = static_cast<int>(tri.E.rows());
  const RowPositions rows = V;
  int bad_segment = start(ne);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(min : bad_segment)
  for (int e = 0; e < ne; ++e) {
    TracePoint ends[2];
    int count = 0;
    const TracePoint* points = traces.edge_points(e, tri.E, ends, count);
    for (int m = 0; m + 1 < count; ++m) {
      SegmentVector segment;
      if (!segment_vector(rows, points[m], points[m + 1], segment)) {
        bad_segment = std::min(bad_segment, start(e) + m);
        continue;
      }
      segment.weight = segment_weight(tri.cot_weight(e), tri.length(e), segment.length);
      visit(start(e) + m, e, segment);
    }
  }
  if (bad_segment < start(ne)) throw_segment_error(bad_segment);
}

} // namespace iarap::detail
