// The report of arap_parameterize as named fields: one list, so that every front-end (the CLI's JSON, the
// Python dict) names the same values the same way.
#pragma once
#include "iarap/param/arap_parameterize.h"

namespace iarap {

// Calls visit(name, value) for each field of `report` in a fixed order. Values are std::string (names),
// int, bool, double, std::vector<double> (energies, gradient_norms, elapsed_ms: one per iteration) or
// DistortionRange (area_distortion, angle_distortion). Energies in squared mesh units, gradient norms in
// mesh units, times in milliseconds.
template <typename Visitor> void visit_param_report(const ParamReport& report, Visitor&& visit) {
  const MapDistortion& d = report.distortion;
  const ArapReport& solve = report.solve;
  visit("energy_kind", param_energy_name(report.energy));
  visit("requested_init", param_init_name(report.requested_init));
  visit("init", param_init_name(report.init));
  visit("init_flipped", report.init_flipped);
  visit("init_fallback", report.init_fallback);
  visit("pinned", report.pinned);
  visit("accelerator", arap_accelerator_name(solve.accelerator));
  visit("iterations", solve.iterations);
  visit("converged", solve.converged);
  visit("stop_reason", arap_stop_reason_name(solve.stop_reason));
  visit("initial_energy", solve.initial_energy);
  visit("energies", solve.energies);
  visit("barrier", report.barrier);
  visit("initial_gradient_norm", solve.initial_gradient_norm);
  visit("gradient_norms", solve.gradient_norms);
  visit("rejected", solve.rejected);
  visit("solves", solve.solves);
  visit("elapsed_ms", solve.elapsed_ms);
  visit("energy", d.energy);
  visit("scaled_energy", d.scaled_energy);
  visit("best_scale", d.best_scale);
  visit("flipped", d.flipped);
  visit("min_det_J", d.min_det_J);
  visit("area_distortion", d.area_ratio);
  visit("angle_distortion", d.angle_ratio);
  visit("check_ms", report.check_ms);
  visit("init_ms", report.init_ms);
  visit("cells_ms", report.cells_ms);
  visit("factor_ms", report.factor_ms);
  visit("iterate_ms", report.iterate_ms);
  visit("parameterize_ms", report.total_ms);
}

} // namespace iarap
