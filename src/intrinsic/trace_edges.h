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
  std::vector<int> edge, tail, head; // flipped edges in increasing order, oriented E(e,0) -> E(e,1)
  std::vector<double> phi, length;   // signpost angle at the tail, intrinsic length
};
EdgesToTrace flipped_edges(const SignpostTriangulation& intrinsic);

// One point of a traced edge: (1 - t) V[a] + t V[c], or V[a] alone when c = -1; `face` carries the
// segment to the next point.
struct TracePoint {
  int a, c, face;
  double t;
};

// The traced edges in compact form: points only for the flipped edges. An edge never flipped is its input
// edge, one segment from E(e,0) to E(e,1) carried by input face unflipped_face[e]; on a near-Delaunay mesh
// that is almost every edge, so this holds a fraction of TracedEdges' size (igea: 3% of the edges flip).
// Segments are built from it directly; TracedEdges only when a caller asks for the polylines.
struct CompactTraces {
  std::vector<int> job;            // #E index k among the flipped edges, or -1
  std::vector<int> unflipped_face; // #E input face carrying an unflipped edge, -1 for flipped ones
  std::vector<int> start;          // #flipped + 1 offsets into points
  std::vector<TracePoint> points;

  // Segments over all edges: one per unflipped edge, points - 1 per flipped one.
  int segment_count() const {
    const size_t flipped = start.size() - 1;
    return static_cast<int>(job.size() - flipped + points.size() - flipped);
  }

  // The points of edge e, from E(e,0) to E(e,1): `count` of them at the returned address; an unflipped
  // edge's two are written into `ends`.
  const TracePoint* edge_points(int e, const Eigen::MatrixXi& E, TracePoint (&ends)[2], int& count) const {
    const int k = job[static_cast<size_t>(e)];
    if (k >= 0) {
      count = start[static_cast<size_t>(k) + 1] - start[static_cast<size_t>(k)];
      return points.data() + start[static_cast<size_t>(k)];
    }
    ends[0] = {E(e, 0), -1, unflipped_face[static_cast<size_t>(e)], 0.0};
    ends[1] = {E(e, 1), -1, -1, 0.0};
    count = 2;
    return ends;
  }
};

// Traces every flipped edge as a straight line in the input's flat metric: start at its tail, leave along
// its signpost angle, unfold input triangles until its length is used up, and check that the line ends at
// its head (SolverError naming the edge otherwise). `original_edge` tells the edges never flipped
// (>= 0, the input edge they are). `fans` are the input's vertex fans (from build_signpost_triangulation).
// Parallel over edges.
CompactTraces trace_edges(const InputTriangulation& input, const VertexFans& fans,
                          const EdgesToTrace& flipped, const std::vector<int>& original_edge);

// Every edge's points in CSR form (the public TracedEdges). E: the intrinsic edges (#E x 2).
TracedEdges expand_traces(const CompactTraces& compact, const Eigen::MatrixXi& E);

} // namespace iarap::detail
