#include "stopping.h"

#include "iarap/core/errors.h"

#include <cmath>
#include <string>

namespace iarap::detail {

bool Progress::begin(double energy, double gradient_norm, double local_ms, double global_ms) {
  report_.initial_energy = energy;
  report_.initial_gradient_norm = gradient_norm;
  report_.local_ms += local_ms;
  report_.global_ms += global_ms;
  if (!std::isfinite(energy)) throw SolverError("ARAP: the energy of the initial guess is not finite");
  previous_ = energy;
  report_.converged = options_.gradient_tolerance > 0 && gradient_norm == 0.0;
  if (report_.converged) report_.stop_reason = ArapStopReason::GradientTolerance;
  return report_.converged;
}

bool Progress::record(double energy, double gradient_norm, bool accelerated, double local_ms,
                      double global_ms) {
  report_.iterations += 1;
  report_.energies.push_back(energy);
  report_.gradient_norms.push_back(gradient_norm);
  report_.accepted.push_back(accelerated ? 1 : 0);
  report_.local_ms += local_ms;
  report_.global_ms += global_ms;
  report_.local_ms_per_iteration.push_back(local_ms);
  report_.global_ms_per_iteration.push_back(global_ms);
  report_.elapsed_ms.push_back(ms_since(start_));
  if (!std::isfinite(energy))
    throw SolverError("ARAP: the energy became non-finite at iteration " +
                      std::to_string(report_.iterations) + " (factorization " +
                      factorization_name(factorization_) + ")");
  const double previous = previous_;
  previous_ = energy;
  const bool energy_rule = options_.tolerance >= 0 &&
                           (energy == 0.0 || previous - energy <= options_.tolerance * std::abs(previous));
  const bool gradient_rule = options_.gradient_tolerance > 0 &&
                             gradient_norm <= options_.gradient_tolerance * report_.initial_gradient_norm;
  bool stop = true;
  if (energy_rule || gradient_rule) {
    report_.converged = true;
    report_.stop_reason = energy_rule ? ArapStopReason::EnergyTolerance : ArapStopReason::GradientTolerance;
  } else if (options_.time_budget_ms > 0 && report_.elapsed_ms.back() >= options_.time_budget_ms) {
    report_.stop_reason = ArapStopReason::TimeBudget;
  } else {
    stop = false;
  }
  // The callback sees every iteration, the last included: a caller's own stopping rule (the viewer's
  // refinement, whose chunk of a time budget can be one iteration long) must not miss the iterations that
  // end a solve for another reason.
  if (options_.on_iteration && !options_.on_iteration(report_) && !stop) {
    report_.stop_reason = ArapStopReason::Callback;
    stop = true;
  }
  return stop;
}

} // namespace iarap::detail
