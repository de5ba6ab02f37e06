#include "local_global_loops.h"

#include "accelerator_history.h"
#include "anderson_iteration.h"
#include "hybrid_iteration.h"
#include "lbfgs_iteration.h"
#include "newton_trust_region.h"
#include "plain_iteration.h"
#include "stopping.h"

#include "iarap/core/errors.h"
#include "iarap/solver/solve_option_fields.h"

#include <cmath>
#include <string>

namespace iarap::detail {

void check_solve_options_and_state(const ArapSolveOptions& options) {
  check_solve_options(options); // the schema's fields, with the message every front-end gives
  const double reference = options.newton_reference_gradient; // state, not a field of the schema
  if (!(reference >= 0) || !std::isfinite(reference))
    throw InputError("newton_reference_gradient must be a finite number >= 0; got " +
                     std::to_string(reference));
}

ArapReport run_local_global(Problem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, Clock::time_point start) {
  ArapReport report;
  report.accelerator = options.window == 0 ? ArapAccelerator::None : options.accelerator;
  Progress progress(options, report, factorization, start);
  if (report.accelerator != ArapAccelerator::None && report.accelerator != ArapAccelerator::Newton)
    report.accelerator_history =
        continued_history(options, report.accelerator, problem.free_count() * problem.dimension());
  ArapAcceleratorHistory* history = report.accelerator_history.get();
  // Newton prepares the Hessian after nearly every local step; so does the hybrid once it has switched.
  if (report.accelerator == ArapAccelerator::Newton ||
      (report.accelerator == ArapAccelerator::Hybrid && history->newton_phase))
    problem.keep_covariances();
  double local_ms = 0, global_ms = 0;
  const double energy = timed(local_ms, [&] { return problem.local_step(); });
  // The gradient itself only for the loops that step along it; plain and Anderson read its norm.
  const bool steps_along_gradient =
      report.accelerator != ArapAccelerator::None && report.accelerator != ArapAccelerator::Anderson;
  Eigen::MatrixXd g;
  const double gradient_norm = timed(global_ms, [&] {
    if (!steps_along_gradient) return rhs_and_gradient_norm(problem);
    problem.assemble_rhs();
    g = problem.gradient();
    return g.norm();
  });
  if (progress.begin(energy, gradient_norm, local_ms, global_ms)) return report;
  switch (report.accelerator) {
  case ArapAccelerator::None:
    run_plain(problem, options, progress);
    break;
  case ArapAccelerator::Anderson:
    run_anderson(problem, options, energy, *history->anderson, report, progress);
    break;
  case ArapAccelerator::Lbfgs: {
    double e = energy;
    run_lbfgs(problem, options, e, g, *history->lbfgs, report, progress);
    break;
  }
  case ArapAccelerator::Newton:
    run_newton(problem, options, energy, std::move(g), report, progress);
    break;
  case ArapAccelerator::Hybrid:
    run_hybrid(problem, options, energy, std::move(g), *history, report, progress);
    break;
  }
  report.solves = problem.solves();
  return report;
}

} // namespace iarap::detail
