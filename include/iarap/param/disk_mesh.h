// A mesh checked to be a topological disk and prepared for flattening: its one boundary loop and the
// triangle frames every map of this module is built from.
#pragma once
#include "iarap/param/triangle_frames.h"

#include <Eigen/Core>
#include <vector>

namespace iarap {

struct DiskMesh {
  Eigen::MatrixXd V;         // #V x 3
  Eigen::MatrixXi F;         // #F x 3
  std::vector<int> boundary; // the boundary loop, in the faces' orientation (boundary_loops)
  TriangleFrames frames;     // triangle_frames(V, F)
  double area = 0;           // total surface area
};

// The array errors (InputError), each naming its element: V not #V x 3, F not #F x 3, no faces, a NaN or Inf
// coordinate, a face index out of range.
void check_param_arrays(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Checks (V, F) and prepares it. A single chart flattens only a disk: one connected component, one
// boundary loop, genus 0 (Euler characteristic V - E + F = 1). Throws
// - InputError: V not #V x 3 or F not #F x 3, no faces, a face index out of range, a NaN or Inf
//   coordinate (each naming the face or vertex);
// - TopologyError: what check_mesh finds unusable (non-manifold edges or vertices, inconsistent
//   orientation, repeated vertices in a face), a face of zero area (area <= 1e-12 * bbox diagonal^2) or a
//   vertex no face uses (each naming the first one; repair_mesh removes both), several components, a
//   closed mesh, several boundary loops or genus > 0. The topology messages say what the mesh has
//   (components, boundary loops, genus) and that it must be cut into disks first.
DiskMesh prepare_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// prepare_disk for a chart its caller built as a disk out of a mesh it checked (uv_atlas: an oriented
// manifold without degenerate faces, charts grown under a disk rule): check_mesh's checks are skipped, and
// only the Euler characteristic and the single boundary loop are verified (TopologyError otherwise).
DiskMesh prepare_chart_disk(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

} // namespace iarap
