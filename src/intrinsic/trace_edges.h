// Internal: traces the edges of a flipped signpost triangulation over the input triangulation.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "signpost_triangulation.h"

namespace iarap::detail {

// Traces every edge of `intrinsic` (flipped from `input`) as a straight line in the input's flat metric:
// start at the edge's tail, leave along its signpost angle, unfold input triangles until its length is
// used up, and check that the line ends at the edge's head (SolverError naming the edge otherwise).
// Edges never flipped are copied as one input edge. `fans` are the input's vertex fans (from
// build_signpost_triangulation). Parallel over edges.
TracedEdges trace_edges(const SignpostTriangulation& input, const VertexFans& fans,
                        const SignpostTriangulation& intrinsic);

} // namespace iarap::detail
