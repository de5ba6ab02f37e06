// The report of a simulation step as named fields: one list, so that every front-end (the CLI's
// simulation.json, the Python dict of Simulation.step) names the same values the same way.
#pragma once
#include "iarap/dynamics/simulation.h"
#include "iarap/solver/solve_report_fields.h"

namespace iarap {

// Calls visit(name, value) for each field of `report`: the step's own (step, time, kinetic_energy, and
// elastic_energy, potential_energy, total_energy, the names the per-step reports had before they carried the
// solve), then the solve's (visit_arap_report: iterations, converged, stop_reason, energies, ...). Values as
// visit_arap_report's; energies in mass x (mesh units / time)^2, times in milliseconds.
template <typename Visitor>
void visit_simulation_step_report(const SimulationStepReport& report, Visitor&& visit) {
  const ArapReport& solve = report.solve;
  visit("step", report.step);
  visit("time", report.time);
  visit("kinetic_energy", report.kinetic_energy);
  visit("elastic_energy", solve.arap_energy);
  visit("potential_energy", solve.potential);
  visit("total_energy", report.kinetic_energy + solve.arap_energy + solve.potential);
  visit_arap_report(solve, visit);
}

} // namespace iarap
