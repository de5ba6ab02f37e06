#include "plain_iteration.h"

#include "iarap/core/stopwatch.h"

namespace iarap::detail {

void run_plain(Problem& problem, const ArapSolveOptions& options, Progress& progress) {
  for (int k = 0; k < options.max_iterations; ++k) {
    double local_ms = 0, global_ms = 0;
    timed(global_ms, [&] { problem.set_positions(problem.plain_step()); });
    const double energy = timed(local_ms, [&] { return problem.local_step(); });
    const double gradient_norm = timed(global_ms, [&] { return rhs_and_gradient_norm(problem); });
    if (progress.record(energy, gradient_norm, false, local_ms, global_ms)) return;
  }
}

} // namespace iarap::detail
