// The names of the energies and accelerators (arap_types.h) as the CLI, the scenario files, the server
// and the Python module spell them.
#include "iarap/core/errors.h"
#include "iarap/solver/arap_types.h"

namespace iarap {

ArapMethod parse_arap_method(const std::string& name) {
  if (name == "arap") return ArapMethod::Arap;
  if (name == "spokes-rims") return ArapMethod::SpokesRims;
  if (name == "iarap") return ArapMethod::Iarap;
  throw InputError("unknown ARAP method '" + name + "'; expected arap, spokes-rims or iarap");
}

std::string arap_method_name(ArapMethod method) {
  switch (method) {
  case ArapMethod::Arap:
    return "arap";
  case ArapMethod::SpokesRims:
    return "spokes-rims";
  case ArapMethod::Iarap:
    return "iarap";
  }
  return "unknown";
}

ArapAccelerator parse_arap_accelerator(const std::string& name) {
  if (name == "none") return ArapAccelerator::None;
  if (name == "anderson") return ArapAccelerator::Anderson;
  if (name == "lbfgs") return ArapAccelerator::Lbfgs;
  if (name == "newton") return ArapAccelerator::Newton;
  if (name == "hybrid") return ArapAccelerator::Hybrid;
  throw InputError("unknown ARAP accelerator '" + name +
                   "'; expected anderson, lbfgs, newton, hybrid or none");
}

std::string arap_accelerator_name(ArapAccelerator accelerator) {
  switch (accelerator) {
  case ArapAccelerator::None:
    return "none";
  case ArapAccelerator::Anderson:
    return "anderson";
  case ArapAccelerator::Lbfgs:
    return "lbfgs";
  case ArapAccelerator::Newton:
    return "newton";
  case ArapAccelerator::Hybrid:
    return "hybrid";
  }
  return "none";
}

std::string arap_stop_reason_name(ArapStopReason reason) {
  switch (reason) {
  case ArapStopReason::MaxIterations:
    return "max_iterations";
  case ArapStopReason::EnergyTolerance:
    return "energy_tolerance";
  case ArapStopReason::GradientTolerance:
    return "gradient_tolerance";
  case ArapStopReason::TimeBudget:
    return "time_budget";
  case ArapStopReason::Callback:
    return "callback";
  }
  return "max_iterations";
}

} // namespace iarap
