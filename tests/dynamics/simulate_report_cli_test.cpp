// `iarap simulate`'s per_step entries carry the step's solve report (visit_simulation_step_report): every
// field of deform's report under the same name, with sane values, beside the step's own fields.
#include "app/cli_runner.h"
#include "dynamics/dynamics_fixtures.h"
#include "iarap/io/write_mesh.h"
#include "iarap/solver/solve_report_fields.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace iarap::test {
namespace {

using namespace iarap::test::cli;

TEST(SimulateReportCli, EachStepHasTheSolveReport) {
  const std::filesystem::path dir = temp_dir("simulate_report");
  const HeldPatch patch = held_patch(8);
  const std::filesystem::path mesh = dir / "patch.obj", scenario = dir / "held.json", out = dir / "frames";
  write_mesh(mesh.string(), patch.mesh.V, patch.mesh.F);
  write_file(scenario, R"({"fixed": {"bottom": 0.1, "axis": "y"}})");
  const CliRun run =
      iarap_cli("simulate '" + mesh.string() + "' --scenario '" + scenario.string() + "' --out-dir '" +
                out.string() + "' --gravity 0 0 -1 --dt 0.1 --steps 3 --quiet --json --threads 1");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  ASSERT_EQ(j["per_step"].size(), 3u);
  const std::set<std::string> reasons = {"max_iterations", "energy_tolerance", "gradient_tolerance",
                                         "time_budget", "callback"};
  for (const nlohmann::json& step : j["per_step"]) {
    SCOPED_TRACE(step.dump());
    visit_arap_report(ArapReport{},
                      [&](const char* name, const auto&) { EXPECT_TRUE(step.contains(name)) << name; });
    for (const char* name :
         {"step", "time", "kinetic_energy", "elastic_energy", "potential_energy", "total_energy"})
      EXPECT_TRUE(step.contains(name)) << name;
    const int iterations = step["iterations"].get<int>();
    EXPECT_GE(iterations, 1);
    EXPECT_TRUE(reasons.count(step["stop_reason"].get<std::string>()));
    EXPECT_EQ(step["energies"].size(), static_cast<size_t>(iterations));
    EXPECT_EQ(step["accelerator"].get<std::string>(), "newton");
    // The old names and the report's name the same values; the last energy is Phi = E + inertia + potential.
    const double elastic = step["elastic_energy"].get<double>(),
                 potential = step["potential_energy"].get<double>();
    EXPECT_EQ(step["arap_energy"].get<double>(), elastic);
    EXPECT_EQ(step["potential"].get<double>(), potential);
    const double penalty = step["penalty"].get<double>();
    EXPECT_GT(penalty, 0.0);
    EXPECT_NEAR(step["energies"].back().get<double>(), elastic + penalty + potential,
                1e-10 * (std::abs(elastic) + penalty + std::abs(potential)));
  }
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace iarap::test
