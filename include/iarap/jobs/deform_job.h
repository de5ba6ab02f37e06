// The deformation pipeline as a library call, so that every front-end (`iarap deform`, batch jobs through
// it, Python, the server) gives the same numbers for the same input:
//
//   DeformScene scene = prepare_deform(mesh, constraints_or_scenario, {.repair = true});  // repair, remap
//   ... a front-end reports scene.check's errors and warnings in its own words ...
//   DeformResult result = solve_deform(scene, arap_options, solve_options, forces);       // normalize, solve
//
// prepare_deform repairs the mesh on request (repair_mesh with zero-area faces removed) and carries the
// constraints over: a scenario is resolved on the repaired mesh (its regions cannot select a vertex the
// repair drops), a constraints set is remapped (remap_constraints), the copies of a constrained vertex the
// repair split are constrained too, and per-vertex forces are carried over (added where vertices weld).
// solve_deform divides the mesh by a power of two that brings its coordinates near 1 (exact: squared
// lengths neither overflow nor underflow at 1e+-80), decides the planar mode (a mesh and targets in z = 0),
// precomputes, solves and returns positions and report in the input's units.
#pragma once
#include "iarap/io/read_mesh.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/constraint_set.h"
#include "iarap/scene/scenario.h"
#include "iarap/solver/arap.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace iarap {

// Where the constraints come from: a scenario (resolved on the mesh as prepared) or a constraints set.
struct DeformConstraints {
  std::optional<Scenario> scenario;
  ConstraintSet set; // used when there is no scenario
};

// The statics' external forces (deform --gravity / --forces / --density): the minimum of
// E_ARAP + P - f . (U - V) with f_i = m_i g + the scene's per-vertex forces, m the lumped masses of the
// method (arap_vertex_masses).
struct StaticForces {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero(); // mesh units / time^2
  double density = 1.0;                              // mass = density x area
  bool present = false; // false: the plain deformation (the scene's per-vertex forces are ignored)
};

struct DeformPrepareOptions {
  bool repair = false;
};

// The mesh and constraints a solve runs on, and what the checks found.
struct DeformScene {
  MeshData mesh;             // repaired when asked
  ConstraintSet constraints; // resolved or remapped onto mesh
  Eigen::MatrixXd forces;    // #V x 3 per-vertex forces on mesh (0 x 0: none)
  Eigen::VectorXd stiffness; // #V per-vertex stiffness on mesh (empty: none; ArapOptions::stiffness)
  std::vector<std::vector<int>> rigid_groups; // rigid parts on mesh (empty: none; ArapOptions::rigid_groups)
  std::vector<std::string> repairs;           // RepairResult::actions (empty without repair)
  MeshReport check;                           // check_mesh(mesh): a front-end refuses it when !check.usable()
  // With repair: the input mesh and the maps between its numbering and mesh's (RepairResult's), for
  // in_input_numbering. Empty without repair.
  MeshData input;
  Eigen::VectorXi old_to_new, new_to_old;
  // A tetrahedral mesh (prepare_tet_deform): #T x 4, mesh.F then holds its boundary faces and the solve is
  // volumetric (arap_tets.h). Empty: a surface.
  Eigen::MatrixXi tets;
};

// Repairs on request and carries the constraints, forces and stiffness over. forces: #V x 3 per-vertex
// forces of the input mesh, or 0 x 0; stiffness: #V factors (ArapOptions::stiffness), or empty. Where the
// repair welds vertices their forces add up and the stiffest factor is kept; split copies keep their
// vertex's. Throws what resolve_scenario, remap_constraints and repair_mesh throw.
DeformScene prepare_deform(MeshData mesh, const DeformConstraints& constraints,
                           const DeformPrepareOptions& options = {},
                           Eigen::MatrixXd forces = Eigen::MatrixXd(),
                           Eigen::VectorXd stiffness = Eigen::VectorXd());

// The scene of a tetrahedral mesh (read_tet_mesh): mesh.V = tets.V, mesh.F = tet_boundary_faces(tets.T)
// (soft points on faces and surface outputs use them), scene.tets = tets.T; constraints, forces and
// stiffness are per vertex as for a surface. No repair; check holds the counts and the bounding box (the
// reader has checked the tetrahedra). Throws what resolve_scenario throws.
DeformScene prepare_tet_deform(TetMesh tets, const DeformConstraints& constraints,
                               Eigen::MatrixXd forces = Eigen::MatrixXd(),
                               Eigen::VectorXd stiffness = Eigen::VectorXd());

// The files of a deformation, as `iarap deform` and `iarap.deform_file` take them.
struct DeformFiles {
  std::string mesh;        // .obj .off .ply .stl, or a tetrahedral mesh (.mesh .node .ele .msh)
  std::string scenario;    // exactly one of scenario and constraints
  std::string constraints; // indices in the mesh's file order; `b` lines index its (boundary) faces
  std::string forces;      // optional: `index fx fy fz` lines
  std::string stiffness;   // optional: `index s` lines
  std::string rigid;       // optional: one rigid group per line, `i j k ...` (not with repair)
};

// Reads the files and prepares the scene: prepare_deform for a triangle mesh, prepare_tet_deform for a
// tetrahedral one (repair is for triangle meshes: InputError). Every front-end reads through here, so that
// the same files give the same scene through every door. Throws InputError naming the file (and line) of a
// missing or malformed file, for rigid groups with repair (their indices are the input's), and what the
// prepare functions throw.
DeformScene read_deform_scene(const DeformFiles& files, const DeformPrepareOptions& options = {});

struct DeformResult {
  Eigen::MatrixXd U;           // #V x 3 positions in the input's units
  ArapReport report;           // in the input's units (energies length^2, gradients and trust radius length)
  ArapData data;               // the precomputation: timings, pinned vertices, intrinsic summary, factor
  bool planar = false;         // deformed in the plane z = 0 (ArapOptions::planar)
  double precompute_ms = 0;    // arap_precompute's wall time
  double max_displacement = 0; // max_i |U_i - V_i|, input units
};

// Solves scene with `options` (method, boundary refinement, pin_unconstrained_components; planar is set here,
// and stiffness and rigid groups to the scene's when it has them; a scene with tets runs
// arap_precompute_tets, which refuses methods other than the default, and gravity is refused on it: its
// masses would be the surface's) and `solve` (lengths in mesh units: scale_length_options is applied here).
// With forces.present every connected component must hold a fixed vertex, a soft vertex or a point on a face
// (InputError otherwise: a free body under a force has no equilibrium). Throws what arap_precompute and
// arap_solve throw; a HardPointConflict comes back as InputError naming both lines
// (hard_point_conflict_message), and an energy that overflows as SolverError naming the farthest target.
DeformResult solve_deform(const DeformScene& scene, ArapOptions options, ArapSolveOptions solve,
                          const StaticForces& forces = {});

// Positions U on scene.mesh (#V x 3) written back in the input's numbering (#V_input x 3), to be written
// with scene.input.F (`deform --repair --keep-numbering`): each input vertex at the mean of the copies of
// the vertex that stands for it (a split vertex's copies, a weld's target), or at its input position where
// the repair removed it (an unreferenced vertex). spread (optional): the largest distance of a copy from
// its mean, 0 where nothing was split. Without repair: U.
Eigen::MatrixXd in_input_numbering(const DeformScene& scene, const Eigen::MatrixXd& U,
                                   double* spread = nullptr);

// `iarap deform`'s rule for the planar mode (ArapOptions::planar): a mesh V whose rows, and those of the
// targets, soft targets and forces (each #rows x 3, or 0 x 0), all lie in the plane z = 0 deforms in its
// plane, with rotations about z; anything off the plane makes it a 3D deformation.
bool deforms_in_plane(const Eigen::MatrixXd& V, const Eigen::MatrixXd& targets,
                      const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces);

// The statics' forces on the mesh divided by s (V_scaled = V / s, a power of two; s = 1: the mesh as it
// is): in those units a mass is density s^2 x area and a force f / s, so that the minimizer is the mesh's
// divided by s. m_i g / s (masses of `method`, arap_vertex_masses; none for g = 0) + per_vertex / s
// (#V x 3, or 0 x 0: none). #V x 3. Throws InputError for a density that is not finite and > 0.
Eigen::MatrixXd static_forces(const Eigen::MatrixXd& V_scaled, const Eigen::MatrixXi& F, ArapMethod method,
                              const StaticForces& forces, const Eigen::MatrixXd& per_vertex, double s);

// Throws InputError when a connected component of (#V, F) has no fixed vertex, no soft vertex and no soft
// or hard point on one of its faces: under an external force a free body has no equilibrium.
void require_held_components(const Eigen::MatrixXi& F, int num_vertices, const Eigen::VectorXi& fixed,
                             const Eigen::VectorXi& soft_vertices, const Eigen::VectorXi& soft_faces);

} // namespace iarap
