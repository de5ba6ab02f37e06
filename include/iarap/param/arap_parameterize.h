// ARAP parameterization (Liu, Zhang, Xu, Gotsman and Gortler 2008): the UV map of a disk-like surface
// closest to an isometry, triangle by triangle, flip-free by default.
//
// The energy is E(U) = sum_f area_f ||J_f(U) - R_f||_F^2 over the triangles, J_f the 2x2 Jacobian of the
// map in the triangle's own isometric frame (triangle_frames.h), minimized by the local/global iteration:
// R_f = closest_rotation_2d(J_f) (local), then U minimizing E with the R_f held (global), one
// sparse system L U = sum_f area_f D_f R_f^T with L the cotan Laplacian, factorized once. It is the energy
// libigl's igl::arap (dim 2) and CGAL's ARAP_parameterizer_3 minimize. ParamEnergy::Arap and ::Iarap
// minimize per-vertex energies instead (planar_cells.h: original ARAP's cotan edges or iARAP's segments,
// one 2x2 rotation per vertex), with the same global system structure and the same flip-free steps.
//
// The plain iteration (allow_flips) never increases E: E(U_new) <= E(U_new; R) <= E(U; R) = E(U), the
// rotations minimizing E for a fixed map and the global step minimizing E(.; R). It can fold triangles over
// (det J < 0), as libigl's and CGAL's do.
//
// Flip-free (the default) starts from an injective map and minimizes W = E + sum_f area_f mu psi(det J_f)
// (param_options.h: a barrier only triangles shrunk below eps of their area feel). The iteration is the
// local/global engine of deformation (src/solver: plain, Anderson, L-BFGS or Newton, the same stopping
// rules, time budget and report) on the UV problem of src/param/uv_problem.h: its plain step is the
// Laplacian-preconditioned step, without the barrier exactly the global step, and every step of every
// accelerator goes at most step_fraction of the way to the first map at which some triangle degenerates
// (injective_step.h), so that every iterate keeps every det J_f > 0 while W decreases monotonically.
#pragma once
#include "iarap/param/map_distortion.h"
#include "iarap/param/param_options.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

struct ParamReport {
  ParamEnergy energy = ParamEnergy::Triangle; // the energy minimized (initial_energy, energies)
  ParamInit requested_init = ParamInit::Lscm;
  ParamInit init = ParamInit::Lscm; // the initial map the iteration started from
  int init_flipped = 0;             // flipped triangles of the requested initial map
  bool init_fallback = false;       // it flipped, so the flip-free iteration started from Tutte's map
  bool initial_uv_used = false;     // the iteration started from options.initial_uv (init is then unused)
  // The engine's report (arap_types.h): iterations, converged, stop_reason, accelerator, the minimized
  // energy W of the initial map and after each iteration (initial_energy, energies; W = E + the barrier
  // term when flip-free, E with allow_flips; squared mesh units), gradient norms (mesh units), rejected
  // accelerated steps, solves and times.
  ArapReport solve;
  double barrier = 0; // the barrier term of the final map (W - E; 0 with allow_flips)
  // Of the final map, whatever energy was minimized: distortion.energy is the per-triangle energy (the
  // figure libigl and CGAL report), so that maps minimizing different energies compare.
  MapDistortion distortion;
  int pinned = 0; // vertices held by the global step
  double check_ms = 0, init_ms = 0, cells_ms = 0, factor_ms = 0, iterate_ms = 0, total_ms = 0;
};

struct ParamResult {
  Eigen::MatrixXd UV; // #V x 2, in the units of V
  ParamReport report;
};

// The ARAP parameterization of (V #V x 3, F #F x 3). Runs on V divided by normalizing_scale(V) (exact),
// so any scale works; UV and energies come back in V's units. Throws what prepare_disk throws (InputError,
// TopologyError), InputError for options out of range (the solve options as arap_solve checks them,
// forces or a Newton warm start, step_fraction outside (0, 1), a barrier weight or threshold <= 0, a
// circular boundary with the LSCM start) and SolverError when a system cannot be factorized.
ParamResult arap_parameterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const ParamOptions& options = {});

} // namespace iarap
