// Truncated Newton in a trust region (Steihaug-Toint CG) on E(x) = min_R energy with the exact Hessian
// (Problem::hessian_product), preconditioned by the factorized system matrix. Internal to the solver
// (run_local_global picks it for ArapAccelerator::Newton).
#pragma once
#include "iarap/solver/arap_types.h"

#include "problem.h"
#include "stopping.h"

#include <Eigen/Core>

namespace iarap::detail {

// Newton steps (at most options.window CG steps each) from the problem's current point, whose energy is
// `energy` and gradient g, until report.iterations reaches options.max_iterations or a stopping rule holds.
// The ||g_0|| of CG's forcing term is ArapSolveOptions::newton_reference_gradient when set (a continued
// solve), else the gradient where the solve began (report.initial_gradient_norm).
void run_newton(Problem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
                ArapReport& report, Progress& progress);

} // namespace iarap::detail
