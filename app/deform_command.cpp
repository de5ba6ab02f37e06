// `iarap deform MESH`: one ARAP deformation from a constraints or scenario file, written to a mesh file.
#include "command_registry.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/remap_constraints.h"
#include "iarap/solver/arap.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>

namespace iarap::cli {
namespace {

struct DeformArguments {
  std::string mesh, constraints, scenario, method = "iarap", boundary = "refine", out, report;
  int iterations = 50;
  double tolerance = 1e-6;
  std::string accel = arap_accelerator_name(ArapSolveOptions{}.accelerator);
  int window = ArapSolveOptions{}.window;
  double grad_tol = ArapSolveOptions{}.gradient_tolerance;
  int threads = 0;
  bool json = false, repair = false, pin_unconstrained = false, quiet = false;
};

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// True when a and b name the same file (following links), or would once written.
bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  if (std::filesystem::exists(a, error) && std::filesystem::exists(b, error)) {
    return std::filesystem::equivalent(a, b, error);
  }
  return std::filesystem::weakly_canonical(a, error) == std::filesystem::weakly_canonical(b, error);
}

// The constraint set of the run, on the mesh as read (before any repair).
ConstraintSet load_constraints(const DeformArguments& args, const Eigen::MatrixXd& V) {
  if (!args.constraints.empty())
    return read_constraints(args.constraints, static_cast<int>(V.rows()));
  return resolve_scenario(read_scenario(args.scenario), V);
}

void run_deform(const DeformArguments& args) {
  if (args.constraints.empty() == args.scenario.empty()) {
    throw CLI::ValidationError("give exactly one of --constraints FILE and --scenario FILE");
  }
  if (same_file(args.out, args.mesh)) {
    throw CLI::ValidationError("--out " + args.out + " is the input mesh; refusing to overwrite it");
  }
  if (!args.report.empty() && (same_file(args.report, args.mesh) || same_file(args.report, args.out))) {
    throw CLI::ValidationError("--report " + args.report + " is the input or output mesh");
  }
  const auto total_start = std::chrono::steady_clock::now();
  nlohmann::json j;
  j["input"] = args.mesh;
  MeshData mesh = read_mesh(args.mesh);
  ConstraintSet constraints = load_constraints(args, mesh.V);
  if (args.repair) {
    RepairResult repaired = repair_mesh(mesh.V, mesh.F);
    constraints = remap_constraints(constraints, repaired.old_to_new);
    mesh.V = std::move(repaired.V);
    mesh.F = std::move(repaired.F);
    j["repair"] = repaired.actions;
  }
  const MeshReport check = check_mesh(mesh.V, mesh.F);
  if (!check.usable()) {
    std::string message = args.mesh + ": mesh not usable for ARAP:";
    for (const auto& error : check.errors)
      message += "\n  " + error;
    throw TopologyError(message + "\n(run `iarap info " + args.mesh + "` for the full report)");
  }
  for (const auto& warning : constraints.warnings)
    std::cerr << "deform: warning: " << warning << "\n";
  if (!args.quiet) {
    for (const auto& warning : check.warnings)
      std::cerr << "deform: mesh warning: " << warning << "\n";
  }

  set_thread_count(args.threads);
  ArapOptions options;
  options.method = parse_arap_method(args.method);
  options.pin_unconstrained_components = args.pin_unconstrained;
  options.intrinsic.refine_boundary = args.boundary == "refine";
  const auto precompute_start = std::chrono::steady_clock::now();
  ArapData data = arap_precompute(mesh.V, mesh.F, constraints.fixed, options);
  const double precompute_ms = elapsed_ms(precompute_start);

  Eigen::MatrixXd U = mesh.V;
  ArapSolveOptions solve_options;
  solve_options.max_iterations = args.iterations;
  solve_options.tolerance = args.tolerance;
  solve_options.accelerator = parse_arap_accelerator(args.accel);
  solve_options.window = args.window;
  solve_options.gradient_tolerance = args.grad_tol;
  const ArapReport report = arap_solve(data, constraints.targets, U, solve_options);
  if (!args.quiet) {
    std::cerr << "deform: " << arap_method_name(options.method) << ", " << mesh.V.rows() << " vertices, "
              << constraints.fixed.size() << " constrained, initial energy " << report.initial_energy << "\n";
    for (int k = 0; k < report.iterations; ++k) {
      std::cerr << "deform: iteration " << k + 1 << "/" << args.iterations << " energy " << report.energies[k]
                << " gradient " << report.gradient_norms[k] << (report.accepted[k] ? " accelerated" : "")
                << " (local " << report.local_ms_per_iteration[k] << " ms, global "
                << report.global_ms_per_iteration[k] << " ms)\n";
    }
    std::cerr << "deform: " << (report.converged ? "converged" : "stopped at the iteration limit") << "\n";
  }
  write_mesh(args.out, U, mesh.F);

  j["method"] = arap_method_name(options.method);
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["constrained"] = constraints.fixed.size();
  j["pinned"] = data.pinned.size();
  j["threads"] = thread_count();
  j["iterations"] = report.iterations;
  j["converged"] = report.converged;
  j["initial_energy"] = report.initial_energy;
  j["energies"] = report.energies;
  j["accelerator"] = arap_accelerator_name(report.accelerator);
  j["window"] = args.window;
  j["initial_gradient_norm"] = report.initial_gradient_norm;
  j["gradient_norms"] = report.gradient_norms; // per iteration, like energies
  j["accepted"] = report.accepted;             // 1: the accelerated iterate was kept
  j["rejected"] = report.rejected;
  j["elapsed_ms"] = report.elapsed_ms; // per iteration, since the solve began
  j["precompute_ms"] = precompute_ms;
  j["intrinsic_ms"] = data.timings.intrinsic_ms;
  j["assembly_ms"] = data.timings.assembly_ms;
  j["factor_ms"] = data.timings.factor_ms;
  j["analyze_ms"] = data.timings.analyze_ms; // overlapped with intrinsic + assembly when threads > 1
  j["factorization"] = factorization_name(arap_factorization(data));
  j["local_ms"] = report.local_ms;
  j["global_ms"] = report.global_ms;
  j["max_displacement"] = (U - mesh.V).rowwise().norm().maxCoeff();
  j["bbox_diagonal"] = check.bbox_diagonal;
  j["output"] = args.out;
  j["total_ms"] = elapsed_ms(total_start);
  if (options.method == ArapMethod::Iarap) {
    j["intrinsic"] = {{"flips", data.intrinsic.flips},
                      {"non_delaunay_before", data.intrinsic.non_delaunay_before},
                      {"non_delaunay_after", data.intrinsic.non_delaunay_after},
                      {"mollify_delta", data.intrinsic.mollify_delta},
                      {"intrinsic_edges", data.intrinsic.intrinsic_edges},
                      {"segments", data.intrinsic.segments},
                      {"boundary", args.boundary},
                      {"obtuse_boundary_before", data.intrinsic.obtuse_boundary_before},
                      {"obtuse_boundary_after", data.intrinsic.obtuse_boundary_after},
                      {"inserted_points", data.intrinsic.inserted_points}};
  }
  const std::string text = j.dump(2) + "\n";
  if (!args.report.empty())
    write_text_file(args.report, text);
  if (args.json)
    std::cout << text;
  if (!args.quiet)
    std::cerr << "deform: wrote " << args.out << "\n";
}

const bool registered = register_command(
    {"deform", [](CLI::App& app) {
       auto args = std::make_shared<DeformArguments>();
       auto* sub = app.add_subcommand(
           "deform", "Deform a mesh with ARAP (original, spokes-and-rims or iARAP), "
                     "starting from the rest shape with constrained vertices at their targets");
       sub->add_option("MESH", args->mesh, "Input mesh (.obj .off .ply .stl)")
           ->required()
           ->check(CLI::ExistingFile);
       auto* constraints =
           sub->add_option("--constraints", args->constraints, "Constraints file: 'index x y z' per line")
               ->check(CLI::ExistingFile);
       auto* scenario = sub->add_option("--scenario", args->scenario, "Scenario file (JSON; see README.md)")
                            ->check(CLI::ExistingFile);
       constraints->excludes(scenario);
       sub->add_option("--method", args->method, "Energy: arap, spokes-rims or iarap")
           ->check(CLI::IsMember({"arap", "spokes-rims", "iarap"}))
           ->capture_default_str();
       sub->add_option("--boundary", args->boundary,
                       "iARAP on meshes with boundary: 'refine' splits boundary edges whose opposite angle is obtuse "
                       "(non-negative weights, stays at rest); 'paper' is the paper's exact discretization")
           ->check(CLI::IsMember({"paper", "refine"}))
           ->capture_default_str();
       sub->add_option("--iterations", args->iterations, "Maximum number of local/global iterations (>= 0)")
           ->check(CLI::Range(0, 1000000))
           ->capture_default_str();
       sub->add_option(
              "--tolerance", args->tolerance,
              "Stop when the energy decreases by at most this fraction of itself in one iteration (>= 0)")
           ->check(CLI::NonNegativeNumber)
           ->capture_default_str();
       sub->add_option("--accel", args->accel, "Accelerator of the local/global iteration: anderson, lbfgs or none")
           ->check(CLI::IsMember({"anderson", "lbfgs", "none"}))
           ->capture_default_str();
       sub->add_option("--window", args->window, "History length of the accelerator (0 = plain iteration)")
           ->check(CLI::Range(0, 1000))
           ->capture_default_str();
       sub->add_option("--grad-tol", args->grad_tol,
                       "Also stop when the gradient norm at the free vertices falls to this fraction of its initial "
                       "value (0 = off)")
           ->check(CLI::NonNegativeNumber)
           ->capture_default_str();
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = all hardware threads")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--out", args->out, "Output mesh (.obj .off .ply), written atomically")->required();
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_flag("--repair", args->repair,
                     "Weld coincident and drop unreferenced vertices first (constraint indices are mapped)");
       sub->add_flag("--pin-unconstrained", args->pin_unconstrained,
                     "Pin one vertex of each connected component that has no constraint (else an error)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       sub->callback([args] { run_deform(*args); });
     }});

} // namespace
} // namespace iarap::cli
