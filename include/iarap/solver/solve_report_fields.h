// The report of arap_solve (ArapReport) as named fields: one list, so that every front-end (the CLI's JSON
// reports, the Python dict, the server's answers) names the same values the same way.
#pragma once
#include "iarap/solver/arap_types.h"

namespace iarap {

// Calls visit(name, value) for each field of `report` in a fixed order. Values are int, bool, double,
// std::string (accelerator and stop reason by name), std::vector<double> (one per iteration) or
// std::vector<unsigned char> (accepted: 1 where the accelerated iterate was kept). Energies in squared mesh
// units, gradient norms and Newton's trust radius in mesh units, times in milliseconds.
template <typename Visitor> void visit_arap_report(const ArapReport& report, Visitor&& visit) {
  visit("iterations", report.iterations);
  visit("converged", report.converged);
  visit("stop_reason", arap_stop_reason_name(report.stop_reason));
  visit("initial_energy", report.initial_energy);
  visit("energies", report.energies);
  visit("penalty", report.penalty);
  visit("potential", report.potential);
  visit("arap_energy", report.arap_energy);
  visit("accelerator", arap_accelerator_name(report.accelerator));
  visit("initial_gradient_norm", report.initial_gradient_norm);
  visit("gradient_norms", report.gradient_norms);
  visit("accepted", report.accepted);
  visit("rejected", report.rejected);
  visit("solves", report.solves);
  visit("local_ms", report.local_ms);
  visit("global_ms", report.global_ms);
  visit("accelerator_ms", report.accelerator_ms);
  visit("local_ms_per_iteration", report.local_ms_per_iteration);
  visit("global_ms_per_iteration", report.global_ms_per_iteration);
  visit("elapsed_ms", report.elapsed_ms);
  visit("newton_trust_radius", report.newton_trust_radius);
  visit("newton_reference_gradient", report.newton_reference_gradient);
}

} // namespace iarap
