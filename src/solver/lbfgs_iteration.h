// L-BFGS on E(x) = min_R energy with H_0 = L_ff^{-1} (Liu, Bouaziz and Kavan 2017), each step checked by
// Armijo backtracking. Internal to the solver (run_local_global picks it for ArapAccelerator::Lbfgs, and
// run_hybrid for its early phase).
#pragma once
#include "iarap/solver/arap_types.h"

#include "lbfgs_direction.h"
#include "problem.h"
#include "stopping.h"

#include <Eigen/Core>

#include <functional>

namespace iarap::detail {

// L-BFGS steps from the problem's current point, whose energy is `energy` and gradient g, continuing the
// pairs in `lbfgs` (ArapSolveOptions::accelerator_history), until report.iterations reaches
// options.max_iterations or a stopping rule holds (returns true), or hand_over(energy) says after an
// iteration that another optimizer should go on (returns false; energy and g are then the last iterate's,
// whose local step and right-hand side are done).
bool run_lbfgs(Problem& problem, const ArapSolveOptions& options, double& energy, Eigen::MatrixXd& g,
               LbfgsDirection& lbfgs, ArapReport& report, Progress& progress,
               const std::function<bool(double)>& hand_over = {});

} // namespace iarap::detail
