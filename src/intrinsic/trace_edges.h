// Internal: traces the edges of a flipped signpost triangulation over the input triangulation.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "signpost_triangulation.h"

namespace iarap::detail {

// The flipped edges of an intrinsic triangulation, which are all the tracer needs of it: an edge never
// flipped is its input edge.
struct EdgesToTrace {
  int num_input_vertices = 0;
  std::vector<int> inserted_halfedge; // where inserted boundary points lie (SignpostTriangulation)
  std::vector<double> inserted_t;
  std::vector<int> edge, tail, head;  // flipped edges in increasing order, oriented E(e,0) -> E(e,1)
  std::vector<double> phi, length;    // signpost angle at the tail, intrinsic length
};
EdgesToTrace flipped_edges(const SignpostTriangulation& intrinsic);

// Traces every flipped edge as a straight line in the input's flat metric: start at its tail, leave along
// its signpost angle, unfold input triangles until its length is used up, and check that the line ends at
// its head (SolverError naming the edge otherwise). Edges never flipped (original_edge >= 0) are written
// as their one input edge, from edge_vertex (SignpostTriangulation's layout). `fans` are the input's vertex
// fans (from build_signpost_triangulation). Parallel over edges.
TracedEdges trace_edges(const InputTriangulation& input, const VertexFans& fans, const EdgesToTrace& flipped,
                        const std::vector<int>& edge_vertex, const std::vector<int>& original_edge);

} // namespace iarap::detail
