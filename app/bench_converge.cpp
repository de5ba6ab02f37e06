#include "bench_converge.h"

#include "iarap/core/threads.h"
#include "iarap/solver/arap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>

namespace iarap::cli {

Scenario band_scenario(const std::string& name, const Eigen::Vector3d& translation_relative,
                       double degrees_about_z) {
  Scenario scenario;
  scenario.source = name;
  Region bottom;
  bottom.kind = RegionKind::Bottom;
  bottom.axis = 1;
  bottom.fraction = 0.1;
  bottom.path = name + ": bottom 10% along y";
  Region top = bottom;
  top.kind = RegionKind::Top;
  top.path = name + ": top 10% along y";
  Handle handle;
  handle.name = "top";
  handle.vertices = {top};
  handle.translation = translation_relative;
  handle.translation_relative = true;
  handle.rotation_axis = Eigen::Vector3d::UnitZ();
  handle.rotation_degrees = degrees_about_z;
  handle.path = top.path;
  scenario.fixed = {bottom};
  scenario.handles = {handle};
  return scenario;
}

Scenario converge_scenario() {
  return band_scenario("converge scenario", Eigen::Vector3d(0.3, -0.1, 0.0), 60);
}

Eigen::MatrixXd drag_start(ArapData& data, const Eigen::MatrixXd& V, int steps) {
  const Scenario full = converge_scenario();
  Eigen::MatrixXd U = V;
  for (int k = 1; k <= steps; ++k) {
    const double share = static_cast<double>(k) / steps;
    const Scenario step = band_scenario("drag step", share * full.handles.front().translation,
                                        share * full.handles.front().rotation_degrees);
    ArapSolveOptions update;
    update.accelerator = ArapAccelerator::None;
    update.max_iterations = 1;
    update.tolerance = -1;
    arap_solve(data, resolve_scenario(step, V).targets, U, update);
  }
  return U;
}

namespace {

ArapSolveOptions run_options(const std::string& accelerator, const ConvergeSettings& settings) {
  ArapSolveOptions options;
  options.accelerator = parse_arap_accelerator(accelerator);
  if (settings.window > 0) options.window = settings.window;
  options.max_iterations = settings.max_iterations;
  options.tolerance = -1; // only the gap (or the gradient rule of the reference run) stops
  return options;
}

// The hybrid's wall time to its switch: the end of its last L-BFGS iteration (0: no switch, or at once).
double newton_from_ms(const ArapReport& report) {
  const auto lbfgs_iterations = static_cast<size_t>(std::max(0, report.newton_from_iteration - 1));
  return lbfgs_iterations > 0 && lbfgs_iterations <= report.elapsed_ms.size()
             ? report.elapsed_ms[lbfgs_iterations - 1]
             : 0.0;
}

} // namespace

nlohmann::json converge_one(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                            const std::string& method, const ConvergeSettings& settings) {
  ArapOptions options;
  options.method = parse_arap_method(method);
  options.pin_unconstrained_components = true; // as the timing bench: meshes with unreached pieces
  const ConstraintSet constraints = resolve_scenario(converge_scenario(), V);
  ArapData data = arap_precompute(V, F, constraints.fixed, options);
  const Eigen::MatrixXd start = settings.drag_steps > 0 ? drag_start(data, V, settings.drag_steps) : V;

  // Reference minimum: the accelerators run to a tiny gradient; the lower energy wins (they may stop in
  // different basins of this non-convex energy, and then the lower one is the one all runs can reach).
  double reference = std::numeric_limits<double>::infinity();
  nlohmann::json reference_runs = nlohmann::json::array();
  for (const std::string& accelerator : settings.reference_accelerators) {
    ArapSolveOptions long_run = run_options(accelerator, settings);
    long_run.gradient_tolerance = settings.reference_gradient;
    Eigen::MatrixXd U = start;
    const ArapReport report = arap_solve(data, constraints.targets, U, long_run);
    const double energy = report.energies.empty() ? report.initial_energy : report.energies.back();
    reference = std::min(reference, energy);
    reference_runs.push_back(
        {{"accelerator", accelerator},
         {"iterations", report.iterations},
         {"energy", energy},
         {"relative_gradient",
          report.gradient_norms.empty() ? 0.0 : report.gradient_norms.back() / report.initial_gradient_norm},
         {"converged", report.converged}});
  }
  const double target = reference + settings.tolerance * std::abs(reference);

  nlohmann::json j;
  j["mesh"] = path;
  j["vertices"] = V.rows();
  j["method"] = method;
  j["threads"] = thread_count();
  j["drag_steps"] = settings.drag_steps;
  j["reference_energy"] = reference;
  j["reference_runs"] = reference_runs;
  j["runs"] = nlohmann::json::array();
  for (const std::string& accelerator : settings.accelerators) {
    ArapSolveOptions run = run_options(accelerator, settings);
    // A run that converges to another stationary point (the energies have several: see docs/accelerators.md)
    // stops there as the reference runs do, instead of iterating on to the limit.
    run.gradient_tolerance = settings.reference_gradient;
    run.on_iteration = [target](const ArapReport& report) { return report.energies.back() > target; };
    Eigen::MatrixXd U = start;
    // Process CPU time (all threads) beside the wall time: on a shared machine it counts the run's own work.
    const std::clock_t cpu_start = std::clock();
    const ArapReport report = arap_solve(data, constraints.targets, U, run);
    const double cpu_ms = 1000.0 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    const bool reached = !report.energies.empty() && report.energies.back() <= target;
    const double ms = report.elapsed_ms.empty() ? 0.0 : report.elapsed_ms.back();
    // The first iterate within the early gap (-1: none).
    const double early_target = reference + settings.early_gap * std::abs(reference);
    const auto early = std::find_if(report.energies.begin(), report.energies.end(),
                                    [early_target](double e) { return e <= early_target; });
    const auto early_k = early - report.energies.begin();
    const bool early_reached = early != report.energies.end();
    j["runs"].push_back(
        {{"accelerator", accelerator},
         {"window", accelerator == "none" ? 0 : run.window},
         {"iterations", report.iterations},
         {"ms", ms},
         {"cpu_ms", cpu_ms},
         {"ms_per_iteration", report.iterations > 0 ? ms / report.iterations : 0.0},
         {"accelerator_ms", report.accelerator_ms},
         {"rejected", report.rejected},
         {"solves", report.solves},
         {"reached", reached},
         {"early_gap", settings.early_gap},
         {"early_iterations", early_reached ? static_cast<int>(early_k) + 1 : -1},
         {"early_ms", early_reached ? report.elapsed_ms[static_cast<size_t>(early_k)] : -1.0},
         {"newton_from", report.newton_from_iteration},
         {"newton_from_ms", newton_from_ms(report)},
         {"stationary", !reached && report.converged},
         {"final_energy", report.energies.empty() ? report.initial_energy : report.energies.back()},
         {"final_gap",
          (report.energies.empty() ? report.initial_energy : report.energies.back()) - reference}});
  }
  return j;
}

void print_converge_table(const nlohmann::json& results, double tolerance) {
  std::printf("iterations and milliseconds to an energy within %.0e (relative) of the reference minimum\n",
              tolerance);
  std::printf("%-28s %-12s %-9s %10s %7s %12s %10s %9s %9s %9s %8s %10s %8s\n", "mesh", "method", "accel",
              "iterations", "solves", "ms", "ms/iter", "x iter", "x time", "overhead", "rejected", "early ms",
              "x early");
  for (const auto& r : results) {
    std::string name = r["mesh"].get<std::string>();
    if (name.size() > 28) name = "..." + name.substr(name.size() - 25);
    if (r.contains("error")) { // a mesh or method that could not be run (bench_command's error_entry)
      std::printf("%-28s %-12s error: %s\n", name.c_str(), r["method"].get<std::string>().c_str(),
                  r["error"].get<std::string>().c_str());
      continue;
    }
    const nlohmann::json* plain = nullptr;
    for (const auto& run : r["runs"])
      if (run["accelerator"] == "none") plain = &run;
    for (const auto& run : r["runs"]) {
      std::printf("%-28s %-12s %-9s %9d%s %7d %12.1f %10.3f", name.c_str(),
                  r["method"].get<std::string>().c_str(), run["accelerator"].get<std::string>().c_str(),
                  run["iterations"].get<int>(),
                  run["reached"].get<bool>()       ? " "
                  : run.value("stationary", false) ? "*"
                                                   : "+",
                  run["solves"].get<int>(), run["ms"].get<double>(), run["ms_per_iteration"].get<double>());
      if (plain && run["accelerator"] != "none" && run["iterations"].get<int>() > 0) {
        // Ratios only for a run that reached the gap; '>' where plain did not (a lower bound).
        const bool reached = run["reached"].get<bool>();
        const char* bound = (*plain)["reached"].get<bool>() ? " " : ">";
        // Per solve, the unit of work: one per plain, Anderson or L-BFGS iteration, one per Newton CG step.
        const double ms_per_solve = run["ms"].get<double>() / std::max(1, run["solves"].get<int>());
        const double overhead = 100.0 * (ms_per_solve / (*plain)["ms_per_iteration"].get<double>() - 1);
        if (reached)
          std::printf(" %s%8.2f %s%8.2f %8.1f%%", bound,
                      (*plain)["iterations"].get<double>() / run["iterations"].get<double>(), bound,
                      (*plain)["ms"].get<double>() / run["ms"].get<double>(), overhead);
        else
          std::printf(" %9s %9s %8.1f%%", "-", "-", overhead);
      } else {
        std::printf(" %9s %9s %9s", "", "", "");
      }
      std::printf(" %8d", run["rejected"].get<int>());
      // The early gap: ms to it, and plain's ms over this run's ('-': not reached).
      const double early_ms = run.value("early_ms", -1.0);
      const double plain_early = plain ? plain->value("early_ms", -1.0) : -1.0;
      if (early_ms >= 0)
        std::printf(" %10.1f", early_ms);
      else
        std::printf(" %10s", "-");
      if (early_ms > 0 && plain_early > 0 && run["accelerator"] != "none")
        std::printf(" %8.2f\n", plain_early / early_ms);
      else
        std::printf(" %8s\n", "");
    }
  }
  std::printf(
      "(x iter, x time: plain / accelerated; solves: back-substitutions with the factor (newton: one per "
      "CG step); overhead: ms per solve over plain's ms per iteration; '+': the gap was not reached within "
      "the iteration "
      "limit; '*': the run converged (relative gradient %.0e) to another stationary point, energy in the "
      "JSON's final_energy; early ms: to a gap of %.0e, x early: plain's early ms over the run's)\n",
      ConvergeSettings{}.reference_gradient, ConvergeSettings{}.early_gap);
}

} // namespace iarap::cli
