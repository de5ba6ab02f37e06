// `iarap bench --converge TOL`: iterations and wall time of the accelerators to reach an energy within TOL
// (relative) of a reference minimum, on the issue-17 scene.
#pragma once
#include "iarap/scene/scenario.h"
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace iarap::cli {

// Bottom 10% along y fixed; the top 10% along y turned about z around its centroid, then moved by
// translation_relative bbox diagonals. `name` is the scenario's source in error messages.
Scenario band_scenario(const std::string& name, const Eigen::Vector3d& translation_relative,
                       double degrees_about_z);

// The convergence scene: bottom 10% along y fixed; the top 10% along y turned 60 degrees about z around its
// centroid and moved by (0.3, -0.1, 0) bbox diagonals (data/bend60_scenario.json).
Scenario converge_scenario();

struct ConvergeSettings {
  double tolerance = 1e-6; // energy gap E - E* <= tolerance |E*|
  std::vector<std::string> accelerators = {"none", "anderson", "lbfgs", "newton", "hybrid"};
  int window = 0;                   // 0: ArapSolveOptions' default
  int max_iterations = 20000;       // per run, the plain one included
  double reference_gradient = 1e-9; // the reference run stops at this relative gradient norm
  // Each run also records when it first came within this gap (iterations and ms; when above `tolerance`):
  // the early phase and the end-game from one run (issue 48: 1e-2 and 1e-6).
  double early_gap = 1e-2;
  // Where every run starts: 0, the rest shape; N > 0, the end of a drag (drag_start): the viewer's
  // refinement after a drag starts there, near the minimum but not at it (issue 48's 173K armadillo).
  int drag_steps = 0;
  // The accelerators of the reference run (the lowest energy wins); fewer on large meshes, where each
  // costs minutes.
  std::vector<std::string> reference_accelerators = {"newton", "lbfgs", "anderson"};
};

// The end of a drag on the convergence scene: the handle turned and moved to its place in `steps` equal
// steps, each answered by one plain iteration from the last answer (what a 20-30 ms update buys on the
// 173K armadillo, docs/performance.md "Dragging in the viewer"), from the rest shape V.
Eigen::MatrixXd drag_start(ArapData& data, const Eigen::MatrixXd& V, int steps);

// One mesh and method: precompute, a long reference run (the lowest energy of the reference accelerators
// run to reference_gradient), then one run per accelerator stopped at the gap, all from the same start.
// Returns a JSON record with a "runs" array (accelerator, iterations, ms, cpu_ms (process CPU time, all
// threads), ms_per_iteration, reached, rejected, early_iterations and early_ms at settings.early_gap,
// hybrid's newton_from and newton_from_ms).
nlohmann::json converge_one(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                            const std::string& method, const ConvergeSettings& settings);

// The table of converge_one records, with plain / accelerated ratios.
void print_converge_table(const nlohmann::json& results, double tolerance);

} // namespace iarap::cli
