#include "line_search.h"

#include "iarap/core/stopwatch.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace iarap::detail {

void take_plain_step(Problem& problem, LineStep& step) {
  step.x = timed(step.global_ms, [&]() -> const Eigen::MatrixXd& { return problem.plain_step(); });
  const ScopedTimer timer(step.local_ms);
  problem.set_positions(step.x);
  step.energy = problem.local_step();
}

void lower_of_step_and_plain(Problem& problem, LineStep& step) {
  LineStep plain;
  take_plain_step(problem, plain);
  step.local_ms += plain.local_ms;
  step.global_ms += plain.global_ms;
  if (plain.energy <= step.energy || !(step.energy == step.energy)) {
    step.x = std::move(plain.x);
    step.energy = plain.energy;
    step.accepted = false;
    return;
  }
  const ScopedTimer timer(step.local_ms);
  problem.set_positions(step.x); // back to the shortened step, whose energy is lower
  step.energy = problem.local_step();
}

LineStep armijo_or_plain_step(Problem& problem, const Eigen::MatrixXd& x, const Eigen::MatrixXd& d,
                              double slope, double energy, ArapReport& report) {
  constexpr double kArmijo = 1e-4; // sufficient-decrease constant c_1 (Nocedal & Wright's usual value)
  constexpr int kTrials = 3;
  LineStep step;
  // The feasible set's bound (injective UV maps); 1 for deformation, whose lengths stay bit for bit.
  const double longest = std::min(1.0, problem.step_limit(x, d));
  {
    const ScopedTimer timer(step.local_ms);
    for (int t = 0; t < kTrials && !step.accepted && slope < 0 && longest > 0; ++t) {
      const double alpha = longest * std::ldexp(1.0, -t); // 1, 1/2, 1/4 of it
      step.x = x + alpha * d;
      problem.set_positions(step.x);
      step.energy = problem.local_step();
      step.accepted = step.energy <= energy + kArmijo * alpha * slope; // false for NaN as well
    }
  }
  if (!step.accepted) {
    ++report.rejected;
    take_plain_step(problem, step);
  } else if (longest < 1) {
    lower_of_step_and_plain(problem, step);
  }
  return step;
}

} // namespace iarap::detail
