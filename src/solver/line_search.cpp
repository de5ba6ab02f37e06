#include "line_search.h"

#include "iarap/core/stopwatch.h"

#include <cmath>

namespace iarap::detail {

void take_plain_step(LocalGlobalProblem& problem, LineStep& step) {
  step.x = timed(step.global_ms, [&]() -> const Eigen::MatrixXd& { return problem.plain_step(); });
  const ScopedTimer timer(step.local_ms);
  problem.set_positions(step.x);
  step.energy = problem.local_step();
}

LineStep armijo_or_plain_step(LocalGlobalProblem& problem, const Eigen::MatrixXd& x, const Eigen::MatrixXd& d,
                              double slope, double energy, ArapReport& report) {
  constexpr double kArmijo = 1e-4; // sufficient-decrease constant c_1 (Nocedal & Wright's usual value)
  constexpr int kTrials = 3;
  LineStep step;
  {
    const ScopedTimer timer(step.local_ms);
    for (int t = 0; t < kTrials && !step.accepted && slope < 0; ++t) {
      const double alpha = std::ldexp(1.0, -t); // 1, 1/2, 1/4
      step.x = x + alpha * d;
      problem.set_positions(step.x);
      step.energy = problem.local_step();
      step.accepted = step.energy <= energy + kArmijo * alpha * slope; // false for NaN as well
    }
  }
  if (!step.accepted) {
    ++report.rejected;
    take_plain_step(problem, step);
  }
  return step;
}

} // namespace iarap::detail
