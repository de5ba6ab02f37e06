// Internal: intrinsic_delaunay in two phases, for a caller that overlaps other work with the first.
// arap_precompute runs the flips beside CHOLMOD's symbolic analysis (one thread each on a 2-core machine)
// and the tracing, export and segments after it, on every thread.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "signpost_triangulation.h"

namespace iarap::detail {

// The input's triangulation flipped to Delaunay (and refined at the boundary if asked), with what the
// tracer needs of the unflipped input.
struct FlippedTriangulation {
  VertexFans fans;
  SignpostTriangulation tri;
  InputTriangulation input;
  FlipStats stats;
  RefineStats refine;
  int non_delaunay_after = 0;
  double flip_ms = 0.0;
};

// Phase 1: builds the signpost triangulation of (V, F) and flips it to Delaunay (TopologyError on bad input).
FlippedTriangulation flip_phase(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const IntrinsicOptions& options);

// Phase 2: traces the flipped edges, exports the triangulation and builds the segments; consumes `flipped`
// piece by piece so that its arrays are released as soon as they are no longer needed.
IntrinsicDelaunay trace_phase(const Eigen::MatrixXd& V, FlippedTriangulation&& flipped, const IntrinsicOptions& options);

} // namespace iarap::detail
