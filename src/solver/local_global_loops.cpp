#include "local_global_loops.h"

#include "anderson_iteration.h"
#include "lbfgs_iteration.h"
#include "newton_trust_region.h"
#include "plain_iteration.h"
#include "stopping.h"

#include "iarap/core/errors.h"

#include <cmath>
#include <string>
#include <utility>

namespace iarap::detail {

void check_solve_options(const ArapSolveOptions& options) {
  if (options.max_iterations < 0)
    throw InputError("ARAP: max_iterations must be >= 0, got " + std::to_string(options.max_iterations));
  if (std::isnan(options.tolerance)) throw InputError("ARAP: tolerance is NaN");
  if (!(options.gradient_tolerance >= 0))
    throw InputError("ARAP: gradient_tolerance must be >= 0, got " +
                     std::to_string(options.gradient_tolerance));
  if (options.window < 0)
    throw InputError("ARAP: window must be >= 0, got " + std::to_string(options.window));
  if (!(options.time_budget_ms >= 0) || !std::isfinite(options.time_budget_ms))
    throw InputError("ARAP: time_budget_ms must be a finite number >= 0, got " +
                     std::to_string(options.time_budget_ms));
  for (const auto& [name, value] :
       {std::pair<const char*, double>{"newton_trust_radius", options.newton_trust_radius},
        {"newton_reference_gradient", options.newton_reference_gradient}}) {
    if (!(value >= 0) || !std::isfinite(value))
      throw InputError(std::string("ARAP: ") + name + " must be a finite number >= 0, got " +
                       std::to_string(value));
  }
}

ArapReport run_local_global(Problem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, Clock::time_point start) {
  ArapReport report;
  report.accelerator = options.window == 0 ? ArapAccelerator::None : options.accelerator;
  Progress progress(options, report, factorization, start);
  if (report.accelerator == ArapAccelerator::Newton) // it prepares the Hessian after nearly every local step
    problem.keep_covariances();
  double local_ms = 0, global_ms = 0;
  const double energy = timed(local_ms, [&] { return problem.local_step(); });
  Eigen::MatrixXd g = timed(global_ms, [&]() -> Eigen::MatrixXd {
    problem.assemble_rhs();
    return problem.gradient();
  });
  if (progress.begin(energy, g.norm(), local_ms, global_ms)) return report;
  switch (report.accelerator) {
  case ArapAccelerator::None:
    run_plain(problem, options, progress);
    break;
  case ArapAccelerator::Anderson:
    run_anderson(problem, options, energy, report, progress);
    break;
  case ArapAccelerator::Lbfgs:
    run_lbfgs(problem, options, energy, std::move(g), report, progress);
    break;
  case ArapAccelerator::Newton:
    run_newton(problem, options, energy, std::move(g), report, progress);
    break;
  }
  report.solves = problem.solves();
  return report;
}

} // namespace iarap::detail
