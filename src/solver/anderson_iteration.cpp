#include "anderson_iteration.h"

#include "iarap/core/stopwatch.h"

namespace iarap::detail {

// The accelerated iterate is kept only when its energy is not above the last accepted one; otherwise the
// plain iterate G(x_k) (whose energy is not above it either, by block descent) replaces it and the history
// restarts from there.
void run_anderson(Problem& problem, const ArapSolveOptions& options, double energy,
                  AndersonAcceleration& anderson, ArapReport& report, Progress& progress) {
  Eigen::MatrixXd x = problem.positions(), next(problem.free_count(), problem.dimension());
  for (int k = 0; k < options.max_iterations; ++k) {
    double local_ms = 0, global_ms = 0;
    Eigen::MatrixXd G = timed(global_ms, [&]() -> Eigen::MatrixXd { return problem.plain_step(); });
    const bool combined =
        timed(report.accelerator_ms, [&] { return anderson.step(x.data(), G.data(), next.data()); });
    double trial = 0;
    bool accepted = false;
    if (combined) {
      trial = timed(local_ms, [&] {
        problem.set_positions(next);
        return problem.local_step();
      });
      accepted = trial <= energy; // false for NaN as well
      if (accepted) {
        x.swap(next);
      } else {
        ++report.rejected;
        anderson.reset();
      }
    }
    if (!accepted) {
      trial = timed(local_ms, [&] {
        x = std::move(G);
        problem.set_positions(x);
        return problem.local_step();
      });
    }
    energy = trial;
    const double gradient_norm = timed(global_ms, [&] { return rhs_and_gradient_norm(problem); });
    if (progress.record(energy, gradient_norm, accepted, local_ms, global_ms)) return;
  }
}

} // namespace iarap::detail
