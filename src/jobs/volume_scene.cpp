// volume_scene and enclosed_volume (volume_deform.h): a surface scene made tetrahedral.
#include "iarap/core/errors.h"
#include "iarap/jobs/volume_deform.h"

#include <Eigen/LU>

#include <string>

namespace iarap {

double enclosed_volume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double six_volume = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Matrix3d corners;
    corners << V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2));
    six_volume += corners.determinant();
  }
  return six_volume / 6.0;
}

DeformScene volume_scene(const DeformScene& surface, const TetgenOptions& options) {
  if (surface.tets.rows() > 0) throw InputError("--volume: the mesh is tetrahedral already");
  if (surface.check.boundary_edges > 0)
    throw InputError(
        "--volume needs a closed surface; this one has " + std::to_string(surface.check.boundary_edges) +
        " boundary edges (boundary loops: " + std::to_string(surface.check.boundary_loops) + ")");
  const SoftConstraintSet& soft = surface.constraints.soft;
  if (soft.faces.size() + soft.hard_faces.size() > 0)
    throw InputError("--volume: points on faces (" +
                     std::to_string(soft.faces.size() + soft.hard_faces.size()) +
                     " 'b' lines) are not supported; constrain vertices (fixed or soft) instead");
  TetMesh tets = tetrahedralize_inside(surface.mesh.V, surface.mesh.F, options);
  const Eigen::Index n = surface.mesh.V.rows(), all = tets.V.rows();
  DeformScene scene;
  scene.constraints = surface.constraints; // surface vertices keep their numbers
  if (surface.forces.rows() > 0) {
    scene.forces = Eigen::MatrixXd::Zero(all, 3);
    scene.forces.topRows(n) = surface.forces;
  }
  if (surface.stiffness.size() > 0) {
    scene.stiffness = Eigen::VectorXd::Ones(all);
    scene.stiffness.head(n) = surface.stiffness;
  }
  scene.rigid_groups = surface.rigid_groups;
  scene.mesh.F = tet_boundary_faces(tets.T);
  scene.mesh.V = std::move(tets.V);
  scene.mesh.notes = std::move(tets.notes);
  scene.tets = std::move(tets.T);
  scene.check.vertices = static_cast<int>(all);
  scene.check.faces = static_cast<int>(scene.mesh.F.rows());
  scene.check.bbox_diagonal = surface.check.bbox_diagonal;
  return scene;
}

} // namespace iarap
