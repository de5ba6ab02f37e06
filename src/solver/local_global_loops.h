// The three iterations behind arap_solve on a LocalGlobalProblem: plain local/global, Anderson-accelerated
// and L-BFGS (see ArapAccelerator). Internal to the solver.
#pragma once
#include "iarap/solver/arap.h"

#include "local_global_problem.h"

#include <chrono>

namespace iarap::detail {

// Runs options.accelerator (plain for ArapAccelerator::None or window 0) from the problem's current U.
// start: when arap_solve began (report.elapsed_ms counts from it). Throws SolverError naming the
// iteration and the factorization when an accepted iterate has a non-finite energy.
ArapReport run_local_global(LocalGlobalProblem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, std::chrono::steady_clock::time_point start);

} // namespace iarap::detail
