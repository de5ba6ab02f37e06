// Internal: cuts traced intrinsic edges into segments s = V b (Eq. 7-8) with weights (Eq. 11).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "trace_edges.h"

namespace iarap::detail {

// Segment m of edge e runs from trace point m to m + 1. Its b merges the barycentric vectors of the two
// points (each an input vertex or a point on an input edge of the carrying face), so it has at most three
// non-zeros that sum to 0. weight = cot_weight(e) * length(e) / |s| (Eq. 11); a segment shorter than
// 1e-12 |e| (a trace grazing a vertex) gets weight 0, since its b b^T / |s| term would be unbounded.
// B is assembled only when asked.
Segments build_segments(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri, const CompactTraces& traces,
                        bool assemble_B);

} // namespace iarap::detail
