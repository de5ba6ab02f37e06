#include "intrinsic_overlay.h"

#include "iarap/intrinsic/intrinsic_delaunay.h"

namespace iarap::serve {

IntrinsicOverlay make_intrinsic_overlay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const IntrinsicDelaunay intrinsic = intrinsic_delaunay(V, F);
  const TracedEdges& traces = intrinsic.traces;
  IntrinsicOverlay overlay;
  overlay.start.assign(traces.start.begin(), traces.start.end());
  overlay.a.assign(traces.a.begin(), traces.a.end());
  overlay.c.assign(traces.c.begin(), traces.c.end());
  overlay.t.assign(traces.t.begin(), traces.t.end());
  const Eigen::VectorXi& original = intrinsic.triangulation.original_edge;
  overlay.original.resize(static_cast<std::size_t>(original.size()));
  for (Eigen::Index e = 0; e < original.size(); ++e)
    overlay.original[static_cast<std::size_t>(e)] = original[e] >= 0 ? 1 : 0;
  return overlay;
}

} // namespace iarap::serve
