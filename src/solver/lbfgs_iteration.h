// L-BFGS on E(x) = min_R energy with H_0 = L_ff^{-1} (Liu, Bouaziz and Kavan 2017), each step checked by
// Armijo backtracking. Internal to the solver (run_local_global picks it for ArapAccelerator::Lbfgs).
#pragma once
#include "iarap/solver/arap_types.h"

#include "problem.h"
#include "stopping.h"

#include <Eigen/Core>

namespace iarap::detail {

// Up to options.max_iterations steps (history options.window pairs) from the problem's current point,
// whose energy is `energy` and gradient g.
void run_lbfgs(Problem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
               ArapReport& report, Progress& progress);

} // namespace iarap::detail
