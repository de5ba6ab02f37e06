#include "iarap/jobs/deform_job.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/jobs/soft_constraints.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/repair.h"
#include "iarap/scene/remap_constraints.h"
#include "iarap/scene/remap_scenario.h"
#include "iarap/solver/arap_tets.h"
#include "iarap/solver/solve_option_fields.h"

#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace iarap {
namespace {

// The constraint whose target lies farthest from its rest position, named by where it came from: when
// the energy overflows, this is the target to fix.
std::string farthest_target(const ConstraintSet& constraints, const Eigen::MatrixXd& V) {
  Eigen::Index worst = 0;
  double distance = -1;
  for (Eigen::Index k = 0; k < constraints.fixed.size(); ++k) {
    const double d = (constraints.targets.row(k) - V.row(constraints.fixed(k))).stableNorm();
    if (!(d <= distance)) {
      worst = k;
      distance = d;
    }
  }
  std::ostringstream text;
  text << "the target of vertex " << constraints.fixed(worst) << " lies " << distance
       << " from its rest position";
  if (static_cast<Eigen::Index>(constraints.origins.size()) == constraints.fixed.size())
    text << " (" << constraints.origins[static_cast<std::size_t>(worst)] << ")";
  return text.str();
}

// The solve's forces (static_forces), 0 x 0 without; every body held unless pinned.
Eigen::MatrixXd scaled_forces(const DeformScene& scene, const StaticForces& forces,
                              const ArapSoftConstraints& soft, const Eigen::MatrixXd& V_scaled,
                              const ArapOptions& options, double s) {
  if (!forces.present) return Eigen::MatrixXd();
  if (!options.pin_unconstrained_components) {
    Eigen::VectorXi faces(soft.faces.size() + soft.hard_faces.size()); // a hard point holds its body too
    faces << soft.faces, soft.hard_faces;
    require_held_components(scene.mesh.F, static_cast<int>(scene.mesh.V.rows()), scene.constraints.fixed,
                            soft.vertices, faces);
  }
  return static_forces(V_scaled, scene.mesh.F, options.method, forces, scene.forces, s);
}

// The input's per-vertex stiffness on the repaired mesh: the stiffest of the vertices welded into one; a
// split copy (a new vertex no input vertex maps to) takes its source's.
Eigen::VectorXd carried_stiffness(const Eigen::VectorXd& stiffness, const RepairResult& repaired) {
  Eigen::VectorXd carried = Eigen::VectorXd::Zero(repaired.V.rows());
  for (Eigen::Index v = 0; v < stiffness.size(); ++v)
    if (repaired.old_to_new(v) >= 0)
      carried(repaired.old_to_new(v)) = std::max(carried(repaired.old_to_new(v)), stiffness(v));
  for (Eigen::Index v = 0; v < carried.size(); ++v)
    if (carried(v) == 0.0) carried(v) = stiffness(repaired.new_to_old(v));
  return carried;
}

} // namespace

DeformScene prepare_deform(MeshData mesh, const DeformConstraints& constraints,
                           const DeformPrepareOptions& options, Eigen::MatrixXd forces,
                           Eigen::VectorXd stiffness) {
  if (stiffness.size() > 0) check_arap_stiffness(stiffness, mesh.V.rows()); // before it is carried over
  DeformScene scene;
  if (!options.repair) {
    scene.constraints =
        constraints.scenario ? resolve_scenario(*constraints.scenario, mesh.V) : constraints.set;
    scene.forces = std::move(forces);
    scene.stiffness = std::move(stiffness);
  } else {
    RepairOptions repair_options;
    repair_options.remove_zero_area = true;
    RepairResult repaired = repair_mesh(mesh.V, mesh.F, repair_options);
    if (constraints.scenario) {
      scene.constraints =
          resolve_scenario(remap_scenario(*constraints.scenario, repaired.old_to_new), repaired.V);
      constrain_split_copies(scene.constraints, repaired.new_to_old);
    } else {
      scene.constraints =
          remap_constraints(constraints.set, {repaired.old_to_new, repaired.new_to_old, mesh.F, repaired.F});
    }
    if (forces.rows() > 0) {
      scene.forces = Eigen::MatrixXd::Zero(repaired.V.rows(), 3);
      for (Eigen::Index v = 0; v < forces.rows(); ++v)
        if (repaired.old_to_new(v) >= 0) scene.forces.row(repaired.old_to_new(v)) += forces.row(v);
    }
    if (stiffness.size() > 0) scene.stiffness = carried_stiffness(stiffness, repaired);
    scene.input = mesh;
    scene.old_to_new = std::move(repaired.old_to_new);
    scene.new_to_old = std::move(repaired.new_to_old);
    mesh.V = std::move(repaired.V);
    mesh.F = std::move(repaired.F);
    scene.repairs = std::move(repaired.actions);
  }
  scene.mesh = std::move(mesh);
  scene.check = check_mesh(scene.mesh.V, scene.mesh.F);
  return scene;
}

DeformScene prepare_tet_deform(TetMesh tets, const DeformConstraints& constraints, Eigen::MatrixXd forces,
                               Eigen::VectorXd stiffness) {
  if (stiffness.size() > 0) check_arap_stiffness(stiffness, tets.V.rows());
  DeformScene scene;
  scene.constraints =
      constraints.scenario ? resolve_scenario(*constraints.scenario, tets.V) : constraints.set;
  scene.forces = std::move(forces);
  scene.stiffness = std::move(stiffness);
  scene.mesh.F = tet_boundary_faces(tets.T);
  scene.mesh.V = std::move(tets.V);
  scene.mesh.notes = std::move(tets.notes);
  scene.tets = std::move(tets.T);
  scene.check.vertices = static_cast<int>(scene.mesh.V.rows());
  scene.check.faces = static_cast<int>(scene.mesh.F.rows());
  scene.check.bbox_diagonal = bounding_box_diagonal(scene.mesh.V);
  return scene;
}

DeformResult solve_deform(const DeformScene& scene, ArapOptions options, ArapSolveOptions solve,
                          const StaticForces& forces) {
  if (scene.tets.rows() > 0 && forces.present && forces.gravity != Eigen::Vector3d::Zero())
    throw InputError("gravity on a tetrahedral mesh is not supported yet: the lumped masses are a surface's");
  const MeshData& mesh = scene.mesh;
  const ConstraintSet& constraints = scene.constraints;
  const double s = normalizing_scale(mesh.V);
  const Eigen::MatrixXd V = mesh.V / s;
  const Eigen::MatrixXd targets = constraints.targets / s;
  // Soft weights need no scaling: E_ARAP and W |x - t|^2 both scale with length^2.
  const ArapSoftConstraints soft = soft_constraints_of(constraints.soft);
  const Eigen::MatrixXd soft_targets = soft_targets_of(constraints.soft) / s;
  solve.forces = scaled_forces(scene, forces, soft, V, options, s);
  // In the plane, a cell squeezed through a reflection keeps a 2x2 rotation.
  options.planar = deforms_in_plane(V, targets, soft_targets, solve.forces);
  if (scene.stiffness.size() > 0) options.stiffness = scene.stiffness; // a ratio: no unit to scale
  if (!scene.rigid_groups.empty()) options.rigid_groups = scene.rigid_groups;
  DeformResult result;
  result.planar = options.planar;
  const auto precompute_start = Clock::now();
  result.data = scene.tets.rows() > 0 ? arap_precompute_tets(V, scene.tets, constraints.fixed, soft, options)
                                      : arap_precompute(V, mesh.F, constraints.fixed, soft, options);
  result.precompute_ms = ms_since(precompute_start);

  result.U = V;
  scale_length_options(solve, s);
  try {
    result.report = arap_solve(result.data, targets, soft_targets, result.U, solve);
  } catch (const HardPointConflict& e) {
    throw InputError(hard_point_conflict_message(e, constraints.soft));
  } catch (const SolverError& e) {
    if (std::string(e.what()).find("initial guess is not finite") == std::string::npos) throw;
    throw SolverError(
        "the ARAP energy of the constraints overflows: " + farthest_target(constraints, mesh.V) +
        ", against a mesh of bounding-box diagonal " + std::to_string(scene.check.bbox_diagonal) +
        "; give targets at a distance comparable to the mesh");
  }
  result.max_displacement = (result.U - V).rowwise().norm().maxCoeff() * s; // no overflow at 1e300
  result.U *= s;
  rescale_report(result.report, s);
  return result;
}

Eigen::MatrixXd in_input_numbering(const DeformScene& scene, const Eigen::MatrixXd& U, double* spread) {
  if (spread) *spread = 0.0;
  if (scene.old_to_new.size() == 0) return U;
  // The mean of each input vertex's copies (new vertices standing for it).
  const Eigen::Index n = scene.input.V.rows();
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, 3);
  Eigen::VectorXi count = Eigen::VectorXi::Zero(n);
  for (Eigen::Index v = 0; v < scene.new_to_old.size(); ++v) {
    sum.row(scene.new_to_old(v)) += U.row(v);
    ++count(scene.new_to_old(v));
  }
  Eigen::MatrixXd mean = sum;
  for (Eigen::Index o = 0; o < n; ++o)
    if (count(o) > 0) mean.row(o) /= count(o);
  if (spread)
    for (Eigen::Index v = 0; v < scene.new_to_old.size(); ++v)
      *spread = std::max(*spread, (U.row(v) - mean.row(scene.new_to_old(v))).norm());
  // Each input vertex: the vertex standing for its new index (itself, or its weld target).
  Eigen::MatrixXd out(n, 3);
  for (Eigen::Index o = 0; o < n; ++o)
    out.row(o) = scene.old_to_new(o) < 0
                     ? Eigen::RowVector3d(scene.input.V.row(o))
                     : Eigen::RowVector3d(mean.row(scene.new_to_old(scene.old_to_new(o))));
  return out;
}

bool deforms_in_plane(const Eigen::MatrixXd& V, const Eigen::MatrixXd& targets,
                      const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces) {
  const auto in_plane = [](const Eigen::MatrixXd& X) {
    return X.rows() == 0 || (X.col(2).array() == 0.0).all();
  };
  return in_plane(V) && in_plane(targets) && in_plane(soft_targets) && in_plane(forces);
}

Eigen::MatrixXd static_forces(const Eigen::MatrixXd& V_scaled, const Eigen::MatrixXi& F, ArapMethod method,
                              const StaticForces& forces, const Eigen::MatrixXd& per_vertex, double s) {
  if (!(forces.density > 0) || !std::isfinite(forces.density))
    throw InputError("density must be a finite number > 0; got " + std::to_string(forces.density));
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(V_scaled.rows(), 3);
  if (forces.gravity != Eigen::Vector3d::Zero())
    f = gravity_forces(arap_vertex_masses(V_scaled, F, method, forces.density * s * s), forces.gravity / s);
  if (per_vertex.rows() > 0) f += per_vertex / s;
  return f;
}

void require_held_components(const Eigen::MatrixXi& F, int num_vertices, const Eigen::VectorXi& fixed,
                             const Eigen::VectorXi& soft_vertices, const Eigen::VectorXi& soft_faces) {
  int count = 0;
  const Eigen::VectorXi component = vertex_components(F, num_vertices, &count);
  std::vector<char> held(static_cast<size_t>(count), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) held[static_cast<size_t>(component(fixed(k)))] = 1;
  for (Eigen::Index k = 0; k < soft_vertices.size(); ++k)
    held[static_cast<size_t>(component(soft_vertices(k)))] = 1;
  for (Eigen::Index k = 0; k < soft_faces.size(); ++k)
    held[static_cast<size_t>(component(F(soft_faces(k), 0)))] = 1;
  std::vector<int> size(static_cast<size_t>(count), 0), first(static_cast<size_t>(count), -1);
  for (int v = 0; v < num_vertices; ++v) {
    const auto c = static_cast<size_t>(component(v));
    if (first[c] < 0) first[c] = v;
    ++size[c];
  }
  for (int c = 0; c < count; ++c) {
    const auto k = static_cast<size_t>(c);
    if (held[k] || size[k] < 2) continue; // a vertex used by no face carries no force's work
    throw InputError("connected component " + std::to_string(c) + " (" + std::to_string(size[k]) +
                     " vertices, e.g. vertex " + std::to_string(first[k]) +
                     ") has no constrained vertex: under gravity or external forces a free body has no "
                     "static equilibrium; fix a vertex of it (or simulate its motion: `iarap simulate`, "
                     "iarap.Simulation)");
  }
}

} // namespace iarap
