#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/jobs/deform_job.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_forces.h"
#include "iarap/scene/read_rigid_groups.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/read_stiffness.h"

#include <utility>

namespace iarap {

namespace {

// The scenario or the constraints file, the forces and the stiffness of a mesh of n vertices and
// `faces` faces (the boundary faces of a tetrahedral mesh).
DeformConstraints read_constraints_of(const DeformFiles& files, int n, int faces) {
  if (files.scenario.empty() == files.constraints.empty())
    throw InputError("a deformation needs exactly one of a scenario and a constraints file");
  DeformConstraints constraints;
  if (!files.scenario.empty())
    constraints.scenario = read_scenario(files.scenario);
  else
    constraints.set = read_constraints(files.constraints, n, faces);
  return constraints;
}

Eigen::MatrixXd forces_of(const DeformFiles& files, int n) {
  return files.forces.empty() ? Eigen::MatrixXd() : read_forces(files.forces, n);
}

Eigen::VectorXd stiffness_of(const DeformFiles& files, int n) {
  return files.stiffness.empty() ? Eigen::VectorXd() : read_stiffness(files.stiffness, n);
}

// The mesh, its constraints, forces and stiffness, prepared.
DeformScene read_scene_files(const DeformFiles& files, const DeformPrepareOptions& options) {
  if (is_tet_mesh_path(files.mesh)) {
    if (options.repair)
      throw InputError("repair is for triangle meshes; " + files.mesh + " is a tetrahedral mesh");
    TetMesh tets = read_tet_mesh(files.mesh);
    const auto n = static_cast<int>(tets.V.rows());
    const DeformConstraints constraints =
        read_constraints_of(files, n, static_cast<int>(tet_boundary_faces(tets.T).rows()));
    return prepare_tet_deform(std::move(tets), constraints, forces_of(files, n), stiffness_of(files, n));
  }
  MeshData mesh = read_mesh(files.mesh);
  const auto n = static_cast<int>(mesh.V.rows());
  const DeformConstraints constraints = read_constraints_of(files, n, static_cast<int>(mesh.F.rows()));
  Eigen::MatrixXd forces = forces_of(files, n);
  Eigen::VectorXd stiffness = stiffness_of(files, n);
  return prepare_deform(std::move(mesh), constraints, options, std::move(forces), std::move(stiffness));
}

} // namespace

DeformScene read_deform_scene(const DeformFiles& files, const DeformPrepareOptions& options) {
  if (!files.rigid.empty() && options.repair)
    throw InputError("rigid groups (" + files.rigid +
                     ") name the input's vertices, which a repair renumbers; repair the mesh first (iarap "
                     "repair) and give the groups of the repaired mesh");
  DeformScene scene = read_scene_files(files, options);
  if (!files.rigid.empty())
    scene.rigid_groups = read_rigid_groups(files.rigid, static_cast<int>(scene.mesh.V.rows()));
  return scene;
}

} // namespace iarap
