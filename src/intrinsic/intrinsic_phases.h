// Internal: intrinsic_delaunay in phases, for a caller that needs something else than Segments from the
// traces. arap_precompute runs both phases beside CHOLMOD's analysis and factorization and builds its
// elements straight from the traces (traced_iarap_elements).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "signpost_triangulation.h"
#include "trace_edges.h"
#include "tufted_cover.h"

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
// `input`, when given, is signpost_input(V, F, options.refine_boundary), which the build takes over.
FlippedTriangulation flip_phase(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                const IntrinsicOptions& options, SignpostInput* input = nullptr);

// Phase 1 on the tufted cover (tufted_cover.h): its vertices are the cover's, its "input" faces the cover's.
FlippedTriangulation flip_cover_phase(const TuftedCover& cover, const IntrinsicOptions& options);

// The exported intrinsic triangulation with its traced edges.
struct TracedTriangulation {
  IntrinsicTriangulation triangulation;
  CompactTraces traces;
  double flip_ms = 0.0, trace_ms = 0.0; // as in IntrinsicDelaunay (flip_ms includes the export)
};

// Phase 2: traces the flipped edges and exports the triangulation; consumes `flipped` piece by piece so
// that its arrays are released as soon as they are no longer needed. Segments follow from the result
// (build_segments, segments.h), which reads its edges only: without `with_faces` the faces, their edges,
// corner angles and areas are not exported (IntrinsicTriangulation's F, FE, corner_angle and face_area
// stay empty: 40 bytes per face the solver would write and never read).
TracedTriangulation trace_phase(FlippedTriangulation&& flipped, bool with_faces = true);

} // namespace iarap::detail
