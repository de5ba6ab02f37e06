// The report of arap_parameterize as named fields: one list, so that every front-end (the CLI's JSON, the
// Python dict) names the same values the same way.
#pragma once
#include "iarap/param/arap_parameterize.h"
#include "iarap/solver/solve_report_fields.h"

#include <string_view>

namespace iarap {

// Calls visit(name, value) for each field of `report` in a fixed order: the map's own fields, then the
// engine's (visit_arap_report: iterations, converged, stop_reason, energies, gradient_norms, ...; not the
// penalty, potential and arap_energy of deformation's terms, which a UV map does not have). Values are
// std::string (names), int, bool, double, std::vector<double> (one per iteration), std::vector<unsigned
// char> (accepted) or DistortionRange (area_distortion, angle_distortion). Energies in squared mesh units,
// gradient norms in mesh units, times in milliseconds.
template <typename Visitor> void visit_param_report(const ParamReport& report, Visitor&& visit) {
  const MapDistortion& d = report.distortion;
  const ArapReport& solve = report.solve;
  visit("energy_kind", param_energy_name(report.energy));
  visit("requested_init", param_init_name(report.requested_init));
  visit("init", param_init_name(report.init));
  visit("init_flipped", report.init_flipped);
  visit("init_fallback", report.init_fallback);
  visit("pinned", report.pinned);
  visit("barrier", report.barrier);
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
  visit_arap_report(solve, [&visit](const char* name, const auto& value) {
    const std::string_view field(name);
    if (field != "penalty" && field != "potential" && field != "arap_energy") visit(name, value);
  });
}

} // namespace iarap
