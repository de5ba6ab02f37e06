// The solve options on the command line (app/solve_option_flags.h): `deform` and `simulate` take every
// field of the schema under its flag, show its range and default in --help, refuse a bad value with the
// library's message as a usage error (exit 2), and write the options and the report by their names.
#include "app/cli_runner.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/solver/solve_option_fields.h"
#include "iarap/solver/solve_report_fields.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;
using iarap::ArapSolveOptions;
using iarap::SolveOptionField;

const std::string bunny_mesh = iarap::test::data_path("bunny.off");
const std::string scenario = iarap::test::data_path("bunny_scenario.json");

// The line of `help` that shows `flag`, or "".
std::string help_line(const std::string& help, const std::string& flag) {
  const std::size_t at = help.find("  " + flag + " ");
  if (at == std::string::npos) return "";
  return help.substr(at, help.find('\n', at) - at);
}

void expect_every_flag(const std::string& command, const ArapSolveOptions& defaults) {
  const CliRun run = iarap_cli(command + " --help");
  ASSERT_EQ(run.code, 0) << run.out;
  iarap::visit_solve_option_fields(defaults, [&](const SolveOptionField& field, const auto& value) {
    const std::string line = help_line(run.out, field.flag);
    ASSERT_FALSE(line.empty()) << command << " lacks " << field.flag << "\n" << run.out;
    // CLI11's "  --window INT:an integer in [0, 1000]=8": the range, then the default.
    EXPECT_NE(line.find(iarap::solve_option_range(field) + "=" + iarap::solve_option_value_text(value)),
              std::string::npos)
        << command << ": " << line;
  });
}

TEST(SolveOptionFlags, DeformAndSimulateShowEveryOptionWithItsDefault) {
  expect_every_flag("deform", ArapSolveOptions{});
  expect_every_flag("simulate", iarap::SimulationOptions::default_step_options());
}

TEST(SolveOptionFlags, ABadValueIsAUsageErrorInTheLibrarysWords) {
  const auto dir = iarap::test::temp_dir("solve_option_flags");
  const std::string deform =
      "deform '" + bunny_mesh + "' --scenario '" + scenario + "' --out '" + (dir / "o.obj").string() + "' ";
  const std::string simulate = "simulate '" + bunny_mesh + "' --scenario '" + scenario +
                               "' --dt 0.1 --steps 1 " + "--out-dir '" + (dir / "frames").string() + "' ";
  const std::pair<std::string, std::string> cases[] = {
      {deform + "--tolerance nan", "--tolerance: tolerance must be a finite number; got nan"},
      {deform + "--iterations 1.5", "--iterations: iterations must be an integer in [0, 1000000]; got 1.5"},
      {deform + "--accel fast",
       "--accel: accelerator must be one of newton, hybrid, lbfgs, anderson, none; got fast"},
      {simulate + "--tolerance inf", "--tolerance: tolerance must be a finite number; got inf"},
      {simulate + "--grad-tol -1", "--grad-tol: gradient_tolerance must be a finite number >= 0; got -1"},
      {simulate + "--time-budget x", "--time-budget: time_budget_ms must be a finite number >= 0; got x"},
  };
  for (const auto& [args, message] : cases) {
    const CliRun run = iarap_cli(args, true);
    EXPECT_EQ(run.code, 2) << args << "\n" << run.out;
    EXPECT_NE(run.out.find(message), std::string::npos) << args << "\n" << run.out;
  }
  EXPECT_FALSE(fs::exists(dir / "o.obj"));
  fs::remove_all(dir);
}

// The report's "options" hold each of `given` (a JSON object) at its value.
void expect_options(const nlohmann::json& report, const char* given) {
  const nlohmann::json options = nlohmann::json::parse(given);
  for (const auto& item : options.items())
    EXPECT_EQ(report["options"][item.key()], item.value()) << item.key() << " in " << report["options"];
}

// Every option given reaches the solve (the JSON's "options"), and every field of the report is written.
TEST(SolveOptionFlags, DeformWritesItsOptionsAndTheWholeReport) {
  const auto dir = iarap::test::temp_dir("solve_option_report");
  const CliRun run = iarap_cli(
      "deform '" + bunny_mesh + "' --scenario '" + scenario + "' --out '" + (dir / "o.obj").string() +
      "' --quiet --json --iterations 4 --tolerance -1 --accel lbfgs --window 3 --grad-tol 1e-12 "
      "--time-budget 60000");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  expect_options(j, R"({"iterations": 4, "tolerance": -1.0, "accelerator": "lbfgs", "window": 3,
      "gradient_tolerance": 1e-12, "time_budget_ms": 60000.0})");
  EXPECT_EQ(j["iterations"], 4); // a negative tolerance runs every iteration
  EXPECT_EQ(j["accelerator"], "lbfgs");
  iarap::visit_arap_report(iarap::ArapReport{},
                           [&](const char* name, const auto&) { EXPECT_TRUE(j.contains(name)) << name; });
  fs::remove_all(dir);
}

// simulate takes the options deform takes, --grad-tol and --time-budget included.
TEST(SolveOptionFlags, SimulateTakesEveryOption) {
  const auto dir = iarap::test::temp_dir("solve_option_simulate");
  const CliRun run = iarap_cli("simulate '" + bunny_mesh + "' --scenario '" + scenario +
                               "' --dt 0.1 --steps 1 --quiet --json --out-dir '" + (dir / "frames").string() +
                               "' --iterations 3 --tolerance 0 --accel none --window 0 --grad-tol 1e-3 "
                               "--time-budget 5000");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  expect_options(j, R"({"iterations": 3, "tolerance": 0.0, "accelerator": "none", "window": 0,
      "gradient_tolerance": 1e-3, "time_budget_ms": 5000.0})");
  EXPECT_LE(j["per_step"][0]["iterations"].get<int>(), 3);
  fs::remove_all(dir);
}

} // namespace
