#include "hybrid_iteration.h"

#include "lbfgs_iteration.h"
#include "newton_trust_region.h"

#include <cmath>

namespace iarap::detail {

bool StallRule::stalled(double energy) {
  for (int j = kSpan; j > 0; --j) recent_[j] = recent_[j - 1];
  recent_[0] = energy;
  if (++seen_ <= kSpan) return false;
  const double mean_decrease = (recent_[kSpan] - recent_[0]) / kSpan;
  return mean_decrease <= kStall * std::abs(energy);
}

void run_hybrid(Problem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
                ArapAcceleratorHistory& history, ArapReport& report, Progress& progress) {
  if (!history.newton_phase) {
    StallRule rule;
    rule.stalled(energy); // the starting point counts as the first of the span
    if (run_lbfgs(problem, options, energy, g, *history.lbfgs, report, progress,
                  [&rule](double e) { return rule.stalled(e); }))
      return;
    history.newton_phase = true;
    problem.keep_covariances(); // Newton prepares the Hessian after nearly every local step
  }
  report.newton_from_iteration = report.iterations + 1;
  run_newton(problem, options, energy, std::move(g), report, progress);
}

} // namespace iarap::detail
