// The plain local/global block descent of the paper (Sec. 4.2): U_{k+1,f} = L_ff^{-1} B(U_k), then the
// local step at U_{k+1}. Internal to the solver (run_local_global picks it).
#pragma once
#include "iarap/solver/arap_types.h"

#include "problem.h"
#include "stopping.h"

namespace iarap::detail {

// Up to options.max_iterations plain iterations from the problem's current point, whose local step and
// right-hand side are done.
void run_plain(Problem& problem, const ArapSolveOptions& options, Progress& progress);

} // namespace iarap::detail
