#include "lbfgs_iteration.h"

#include "iarap/core/stopwatch.h"

#include "inner.h"
#include "lbfgs_direction.h"
#include "line_search.h"

namespace iarap::detail {

// The energy is not convex, so each step is checked by Armijo backtracking; when that fails, the plain
// local/global step (with no history the L-BFGS step itself) is taken and the history restarts.
bool run_lbfgs(Problem& problem, const ArapSolveOptions& options, double& energy, Eigen::MatrixXd& g,
               LbfgsDirection& lbfgs, ArapReport& report, Progress& progress,
               const std::function<bool(double)>& hand_over) {
  const auto H0 = [&](const Eigen::MatrixXd& r) { return problem.solve(r); };
  Eigen::MatrixXd x = problem.positions();
  while (report.iterations < options.max_iterations) {
    Eigen::MatrixXd d;
    double slope = 0;
    bool quasi_newton = false;
    {
      const ScopedTimer timer(report.accelerator_ms);
      d = lbfgs.direction(g, H0);
      slope = inner(g, d);
      quasi_newton = lbfgs.pairs() > 0;
      if (quasi_newton && !(slope < 0)) { // not a descent direction: start over with -L_ff^{-1} g
        lbfgs.reset();
        d = -problem.solve(g);
        slope = inner(g, d);
        quasi_newton = false;
      }
    }
    LineStep step = armijo_or_plain_step(problem, x, d, slope, energy, report);
    if (!step.accepted) {
      lbfgs.reset();
      quasi_newton = false;
    }
    energy = step.energy;
    Eigen::MatrixXd g_next = timed(step.global_ms, [&]() -> Eigen::MatrixXd {
      problem.assemble_rhs();
      return problem.gradient();
    });
    timed(report.accelerator_ms, [&] {
      lbfgs.push(step.x, x, g_next, g);
      x.swap(step.x);
      g.swap(g_next);
    });
    if (progress.record(energy, g.norm(), quasi_newton && step.accepted, step.local_ms, step.global_ms))
      return true;
    if (hand_over && hand_over(energy)) return false;
  }
  return true;
}

} // namespace iarap::detail
