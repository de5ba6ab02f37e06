// Anderson-accelerated local/global iteration with the energy safeguard of Peng et al. 2018 (Algorithm 2).
// Internal to the solver (run_local_global picks it for ArapAccelerator::Anderson).
#pragma once
#include "iarap/solver/arap_types.h"

#include "anderson_acceleration.h"
#include "problem.h"
#include "stopping.h"

namespace iarap::detail {

// Up to options.max_iterations iterations from the problem's current point, whose energy is `energy` and
// whose right-hand side is assembled, continuing the differences in `anderson` (history options.window;
// ArapSolveOptions::accelerator_history).
void run_anderson(Problem& problem, const ArapSolveOptions& options, double energy,
                  AndersonAcceleration& anderson, ArapReport& report, Progress& progress);

} // namespace iarap::detail
