// A simulation step's report (simulation.h, simulation_report_fields.h) carries the step's solve: sane
// iterations and stop reason, and energies that match an independent evaluation of the step's terms.
#include "dynamics_fixtures.h"

#include "iarap/dynamics/simulation.h"
#include "iarap/dynamics/simulation_report_fields.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/solve_report_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

namespace iarap::test {
namespace {

class SimulationReportTest : public SingleThreadTest {};

const std::set<std::string> stop_reasons = {"max_iterations", "energy_tolerance", "gradient_tolerance",
                                            "time_budget", "callback"};

// A falling patch: every step moves, so every solve iterates.
TEST_F(SimulationReportTest, EachStepCarriesItsSolve) {
  const HeldPatch p = held_patch(8);
  SimulationOptions options;
  options.dt = 0.1;
  options.gravity = Eigen::Vector3d(0, 0, -1);
  Simulation sim(p.mesh.V, p.mesh.F, p.fixed, options);
  std::vector<char> fixed(static_cast<size_t>(p.mesh.V.rows()), 0);
  for (Eigen::Index k = 0; k < p.fixed.size(); ++k) fixed[static_cast<size_t>(p.fixed(k))] = 1;
  for (int n = 1; n <= 4; ++n) {
    SCOPED_TRACE("step " + std::to_string(n));
    const Eigen::MatrixXd predicted = sim.positions() + options.dt * sim.velocities();
    const SimulationStepReport r = sim.step();
    const ArapReport& solve = r.solve;
    EXPECT_EQ(r.step, n);
    EXPECT_GE(solve.iterations, 1);
    EXPECT_LE(solve.iterations, options.solve.max_iterations);
    EXPECT_TRUE(solve.converged);
    EXPECT_EQ(arap_stop_reason_name(solve.stop_reason), "energy_tolerance");
    EXPECT_EQ(solve.accelerator, options.solve.accelerator);
    EXPECT_EQ(solve.energies.size(), static_cast<size_t>(solve.iterations));
    EXPECT_EQ(solve.gradient_norms.size(), static_cast<size_t>(solve.iterations));
    EXPECT_GE(solve.solves, solve.iterations);
    // The terms of Phi at the new positions, evaluated here: E_ARAP, the potential and the inertia
    // sum_i m_i / (2 h^2) |x_i - x_pred,i|^2 over the free vertices (the report's penalty).
    double inertia = 0;
    for (Eigen::Index v = 0; v < predicted.rows(); ++v)
      if (!fixed[static_cast<size_t>(v)])
        inertia += sim.masses()(v) / (2 * options.dt * options.dt) *
                   (sim.positions().row(v) - predicted.row(v)).squaredNorm();
    const double scale = std::abs(solve.arap_energy) + std::abs(solve.potential) + inertia;
    EXPECT_GT(inertia, 0.0);
    EXPECT_NEAR(solve.arap_energy, sim.elastic_energy(), 1e-10 * scale);
    EXPECT_NEAR(solve.potential, sim.potential_energy(), 1e-10 * scale);
    EXPECT_NEAR(solve.penalty, inertia, 1e-10 * scale);
    EXPECT_NEAR(solve.energies.back(), solve.arap_energy + solve.penalty + solve.potential, 1e-10 * scale);
    EXPECT_LT(solve.potential, 0.0); // the patch fell
  }
}

// The field list: the step's own fields, then every field of the solve's report under its own name.
TEST_F(SimulationReportTest, FieldsAreTheStepsThenTheSolves) {
  const HeldPatch p = held_patch(6);
  SimulationOptions options;
  options.gravity = Eigen::Vector3d(0, -1, 0);
  Simulation sim(p.mesh.V, p.mesh.F, p.fixed, options);
  const SimulationStepReport r = sim.step();
  std::vector<std::string> names,
      expected = {"step", "time", "kinetic_energy", "elastic_energy", "potential_energy", "total_energy"};
  visit_arap_report(r.solve, [&](const char* name, const auto&) { expected.emplace_back(name); });
  double elastic = NAN, total = NAN;
  std::string stop_reason;
  visit_simulation_step_report(r, [&](const char* name, const auto& value) {
    names.emplace_back(name);
    using Value = std::decay_t<decltype(value)>;
    const std::string field(name);
    if constexpr (std::is_same_v<Value, double>) {
      if (field == "elastic_energy") elastic = value;
      if (field == "total_energy") total = value;
    } else if constexpr (std::is_same_v<Value, std::string>) {
      if (field == "stop_reason") stop_reason = value;
    }
  });
  EXPECT_EQ(names, expected);
  EXPECT_EQ(elastic, r.solve.arap_energy);
  EXPECT_EQ(total, r.kinetic_energy + r.solve.arap_energy + r.solve.potential);
  EXPECT_TRUE(stop_reasons.count(stop_reason)) << stop_reason;
}

} // namespace
} // namespace iarap::test
