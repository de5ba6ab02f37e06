// The loop behind arap_solve: the initial local step, then the optimizer ArapSolveOptions::accelerator
// names (plain, Anderson, L-BFGS or Newton, one file each) on a Problem
// (problem.h: deformation's LocalGlobalProblem, parameterization's UvProblem). Internal to the engine.
#pragma once
#include "iarap/core/stopwatch.h"
#include "iarap/solver/arap_types.h"

#include "problem.h"

namespace iarap::detail {

// Throws InputError naming the first option of `options` out of its range: check_solve_options (the
// schema's fields) and Newton's reference gradient, which a solve hands on to the next.
void check_solve_options_and_state(const ArapSolveOptions& options);

// Runs options.accelerator (plain for ArapAccelerator::None or window 0) from the problem's current U.
// start: when arap_solve began (report.elapsed_ms counts from it). Throws SolverError naming the
// iteration and the factorization when an accepted iterate has a non-finite energy.
ArapReport run_local_global(Problem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, Clock::time_point start);

} // namespace iarap::detail
