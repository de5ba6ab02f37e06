// What a solve request asks of the session (SolveRequest) and what it answers (SolveResult): the contract
// between POST /api/solve's parser (solve_routes.cpp) and Session::solve.
#pragma once
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace iarap::serve {

// The server's solve options before a request sets any: the library's, but 5 iterations per answer (an
// interactive update; `refine` goes on in the background).
inline ArapSolveOptions interactive_solve_options() {
  ArapSolveOptions options;
  options.max_iterations = 5;
  return options;
}

// The solve options are the fields of solve_option_fields.h, parsed from the request by their names
// (solve_option_json.h); a new one needs nothing here.
struct SolveRequest {
  ArapMethod method = ArapMethod::Iarap;
  ArapSolveOptions solve = interactive_solve_options(); // max_iterations at most the server's limit
  // Handle targets: anchors moved by transform (4 x 4 affine, last row 0 0 0 1), or given as #handle x 3.
  std::optional<Eigen::Matrix4d> transform;
  std::optional<Eigen::MatrixXd> handle_targets;
  // A soft handle (solver_constraints.h): one weight > 0 per handle vertex, in handle order; none: hard.
  std::optional<Eigen::VectorXd> handle_weights;
  bool cell_energy = false; // also return arap_cell_energy of the result
  // Statics, as `iarap deform --gravity --density --forces`: forces f_i = m_i g (lumped masses of the
  // method, density x area) plus the given per-vertex forces (3 x #V numbers, row-major), and the solve
  // minimizes E_ARAP + P - f . (U - V). No gravity and no forces: the plain deformation.
  std::optional<Eigen::Vector3d> gravity;    // mesh units / time^2
  double density = 1.0;                      // surface density, > 0
  std::optional<std::vector<double>> forces; // 3 x #V numbers (checked against the mesh in solve)
  // > 0: unless the solve converged, keep solving toward the same targets in the background after the
  // answer (same method, accelerator, window and tolerance), at most this many more iterations.
  int refine_iterations = 0;
  // The refinement's accelerator. Newton by default: its end-game is the fastest (beetle, from a drag's
  // last answer: 31 iterations to a 3e-7 gap, where L-BFGS stopped at 5e-5 and Anderson at 6e-4), while
  // the drag's own updates are cheapest with plain iterations (bench/drag_bench.mjs).
  ArapAccelerator refine_accelerator = ArapAccelerator::Newton;
  // Start from the last answer moved on along the drag's motion (drag_motion.h) rather than from the last
  // answer: the viewer's updates while the handle is dragged. Not with soft points or forces.
  bool extrapolate = false;
};

struct SolveResult {
  ArapReport report;
  double wait_ms = 0; // for the session: another request's work, or the refinement's last iteration
  bool refinement_preempted = false; // an unfinished refinement (of an earlier solve) ended for this one
  // The refinement iterations that ended during wait_ms: the preemption's own measure, where wait_ms also
  // holds how long that iteration and the threads' scheduling took (seconds on a loaded machine).
  int refinement_iterations_waited = 0;
  double precompute_ms = 0; // > 0 when this solve built or refactorized the method's data
  double solve_ms = 0;
  int pinned = 0;                 // vertices pinned because their component had no constrained vertex
  bool planar = false;            // solved in the plane z = 0 (the mesh and every target lie in it)
  std::vector<float> positions;   // #V x 3 row-major
  std::vector<float> cell_energy; // #V when requested
  bool cancelled = false;         // POST /api/cancel stopped it early; positions are the last iterate's
  std::uint64_t generation = 0;   // the session generation this solve started
  std::uint64_t sequence = 0;     // its frame's number on the FrameBoard
  bool refining = false;          // the background refinement continues from it
  double extrapolation = 0;       // the scale s the initial guess moved on by (DragMotion; 0: none)
};

} // namespace iarap::serve
