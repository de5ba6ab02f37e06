// `iarap deform MESH`: one ARAP deformation from a constraints or scenario file, written to a mesh file.
#include "command_registry.h"
#include "explain_error.h"
#include "external_force_options.h"
#include "json_text.h"
#include "same_file.h"
#include "soft_constraint_sets.h"
#include "solve_option_flags.h"
#include "solve_report_json.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/remap_constraints.h"
#include "iarap/scene/remap_scenario.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/solve_option_fields.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

namespace iarap::cli {
namespace {

struct DeformArguments {
  std::string mesh, constraints, scenario, method = "iarap", boundary = "refine", out, report;
  ArapSolveOptions solve; // the flags of solve_option_flags.h; forces are set from `forces` below
  int threads = 0;
  bool json = false, repair = false, pin_unconstrained = false, quiet = false;
  ExternalForceArguments forces; // statics under gravity / per-vertex forces (none: the plain deformation)
};

// A constrained vertex that --repair split (one copy per fan or sheet) gets every copy constrained to its
// target: a copy left free would leave its sheet hanging. Copies a geometric region already selected (they
// sit at the vertex's position) stay as they are.
void constrain_split_copies(ConstraintSet& constraints, const RepairResult& repaired) {
  const Eigen::Index n = repaired.V.rows(), count = constraints.fixed.size();
  std::vector<Eigen::Index> row_of(static_cast<std::size_t>(n), -1);
  for (Eigen::Index k = 0; k < count; ++k) row_of[static_cast<std::size_t>(constraints.fixed(k))] = k;
  std::vector<std::pair<int, Eigen::Index>> added; // (copy, row of its constrained first copy)
  for (Eigen::Index v = 0; v < n; ++v) {
    const int first = repaired.old_to_new(repaired.new_to_old(v));
    if (first != v && row_of[static_cast<std::size_t>(v)] < 0 && row_of[static_cast<std::size_t>(first)] >= 0)
      added.emplace_back(static_cast<int>(v), row_of[static_cast<std::size_t>(first)]);
  }
  if (added.empty()) return;
  const auto extra = static_cast<Eigen::Index>(added.size());
  constraints.fixed.conservativeResize(count + extra);
  constraints.targets.conservativeResize(count + extra, 3);
  const bool named = static_cast<Eigen::Index>(constraints.origins.size()) == count;
  for (Eigen::Index i = 0; i < extra; ++i) {
    const auto& [copy, row] = added[static_cast<std::size_t>(i)];
    constraints.fixed(count + i) = copy;
    constraints.targets.row(count + i) = constraints.targets.row(row);
    if (named) constraints.origins.push_back(constraints.origins[static_cast<std::size_t>(row)]);
  }
}

// The mesh to deform and its constraints. With --repair the mesh is repaired first (welded, unreferenced
// vertices and zero-area and duplicate faces dropped, non-manifold edges and vertices split, faces
// oriented consistently: repair_mesh with remove_zero_area) and a scenario is resolved on
// the repaired mesh, so that its regions cannot select a vertex the repair drops; a constraints file's
// indices are carried over.
// The forces file's rows follow the file's vertices and are carried over (added up where vertices weld).
void load_mesh_and_constraints(const DeformArguments& args, MeshData& mesh, ConstraintSet& constraints,
                               Eigen::MatrixXd& forces, nlohmann::json& j) {
  mesh = read_mesh(args.mesh);
  Scenario scenario;
  if (!args.scenario.empty()) scenario = read_scenario(args.scenario);
  forces = file_forces(args.forces, static_cast<int>(mesh.V.rows()));
  if (!args.repair) {
    constraints = args.constraints.empty()
                      ? resolve_scenario(scenario, mesh.V)
                      : read_constraints(args.constraints, static_cast<int>(mesh.V.rows()),
                                         static_cast<int>(mesh.F.rows()));
    return;
  }
  RepairOptions repair_options;
  repair_options.remove_zero_area = true;
  RepairResult repaired = repair_mesh(mesh.V, mesh.F, repair_options);
  if (args.constraints.empty()) {
    constraints = resolve_scenario(remap_scenario(scenario, repaired.old_to_new), repaired.V);
  } else {
    constraints = remap_constraints(
        read_constraints(args.constraints, static_cast<int>(mesh.V.rows()), static_cast<int>(mesh.F.rows())),
        repaired.old_to_new);
  }
  constrain_split_copies(constraints, repaired);
  if (forces.rows() > 0) {
    Eigen::MatrixXd moved = Eigen::MatrixXd::Zero(repaired.V.rows(), 3);
    for (Eigen::Index v = 0; v < forces.rows(); ++v)
      if (repaired.old_to_new(v) >= 0) moved.row(repaired.old_to_new(v)) += forces.row(v);
    forces = std::move(moved);
  }
  mesh.V = std::move(repaired.V);
  mesh.F = std::move(repaired.F);
  j["repair"] = repaired.actions;
}

// Original ARAP's energy is bounded below only with non-negative cotangent weights: on meshes with many
// non-Delaunay edges it can go negative, and the "minimum" then drifts far from a rigid deformation
// (measured on nefertiti: free vertices moved by 0.47 of the diagonal for a handle moved by 0.1).
constexpr double many_negative_weights = 0.1; // share of the edges

void warn_about_original_energy(const ArapReport& report, const MeshReport& check) {
  double lowest = report.initial_energy;
  for (double e : report.energies) lowest = std::min(lowest, e);
  const double share = check.edges > 0 ? static_cast<double>(check.non_delaunay_edges) / check.edges : 0.0;
  if (lowest < 0) {
    std::cerr << "deform: warning: original ARAP's energy went negative: " << check.non_delaunay_edges
              << " edges have negative cotangent weights, so the energy is not bounded below and the result "
                 "can be far from rigid; use --method iarap\n";
  } else if (share >= many_negative_weights) {
    std::cerr << "deform: warning: " << check.non_delaunay_edges << " of " << check.edges
              << " edges have negative cotangent weights; original ARAP's energy is then not bounded below "
                 "and its result can be far from rigid; --method iarap has no negative weights\n";
  }
}

// The constraint whose target lies farthest from its rest position, named by where it came from: when
// the energy overflows, this is the target to fix.
std::string farthest_target(const ConstraintSet& constraints, const Eigen::MatrixXd& V) {
  Eigen::Index worst = 0;
  double distance = -1;
  for (Eigen::Index k = 0; k < constraints.fixed.size(); ++k) {
    const double d = (constraints.targets.row(k) - V.row(constraints.fixed(k))).stableNorm();
    if (!(d <= distance)) {
      worst = k;
      distance = d;
    }
  }
  std::ostringstream text;
  text << "the target of vertex " << constraints.fixed(worst) << " lies " << distance
       << " from its rest position";
  if (static_cast<Eigen::Index>(constraints.origins.size()) == constraints.fixed.size())
    text << " (" << constraints.origins[static_cast<std::size_t>(worst)] << ")";
  return text.str();
}

// External forces (statics): f in the solve's units (the mesh divided by s) for the minimum of
// E_ARAP + P - f . (U - V); 0 x 0 without --gravity and --forces. Every component must be held.
Eigen::MatrixXd statics_forces(const DeformArguments& args, const MeshData& mesh,
                               const Eigen::VectorXi& fixed, const ArapSoftConstraints& soft,
                               const Eigen::MatrixXd& V, ArapMethod method, double s,
                               const Eigen::MatrixXd& forces_in_file) {
  if (!args.forces.any()) return Eigen::MatrixXd();
  if (!args.pin_unconstrained) {
    Eigen::VectorXi faces(soft.faces.size() + soft.hard_faces.size()); // a hard point holds its body too
    faces << soft.faces, soft.hard_faces;
    require_held_components(mesh.F, static_cast<int>(mesh.V.rows()), fixed, soft.vertices, faces);
  }
  return scaled_forces(args.forces, V, mesh.F, method, s, forces_in_file);
}

// The statics' report keys: energy = arap_energy + penalty + potential, potential = -f . (U - V).
void add_statics_keys(const ExternalForceArguments& forces, const ArapReport& report, nlohmann::json& j) {
  j["energy"] = report.arap_energy + report.penalty + report.potential;
  j["gravity"] = forces.gravity.empty() ? std::vector<double>{0.0, 0.0, 0.0} : forces.gravity;
  j["density"] = forces.density;
  j["forces"] = forces.forces;
}

// Before the solve, which can take seconds: exactly one constraints source, and output paths that can be
// written and overwrite no input.
void check_arguments(const DeformArguments& args) {
  if (args.constraints.empty() == args.scenario.empty()) {
    throw CLI::ValidationError("give exactly one of --constraints FILE and --scenario FILE");
  }
  if (same_file(args.out, args.mesh)) {
    throw CLI::ValidationError("--out " + args.out + " is the input mesh; refusing to overwrite it");
  }
  if (!args.report.empty() && (same_file(args.report, args.mesh) || same_file(args.report, args.out))) {
    throw CLI::ValidationError("--report " + args.report + " is the input or output mesh");
  }
  check_mesh_output_path(args.out);
  if (!args.report.empty()) check_output_path(args.report);
}

void require_usable(const DeformArguments& args, const MeshReport& check) {
  if (check.usable()) return;
  std::string message = args.mesh + (args.repair ? ": mesh not usable for ARAP after --repair:"
                                                 : ": mesh not usable for ARAP:");
  for (const auto& error : check.errors) message += "\n  " + name_repair(error, deform_repair_flag);
  throw TopologyError(message + (args.repair ? "\n(numbers refer to the repaired mesh; `iarap info " +
                                                   args.mesh + "` reports the file as it is)"
                                             : "\n(run `iarap info " + args.mesh + "` for the full report)"));
}

ArapData precompute_explained(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const Eigen::VectorXi& fixed, const ArapSoftConstraints& soft,
                              const ArapOptions& options, const ErrorContext& context) {
  try {
    return arap_precompute(V, F, fixed, soft, options);
  } catch (const SolverError& e) {
    throw SolverError(explain_solver_error(e.what(), context));
  } catch (const TopologyError& e) {
    throw TopologyError(explain_solver_error(e.what(), context));
  }
}

// The report of a solve on the mesh divided by s, in the file's units: energies scale with length^2,
// gradients (L U - rhs) and Newton's trust radius (the L_ff norm of a displacement) with length.
void to_file_units(ArapReport& report, double s) {
  const double energy_unit = s * s;
  report.initial_energy *= energy_unit;
  for (double& e : report.energies) e *= energy_unit;
  report.penalty *= energy_unit;
  report.arap_energy *= energy_unit;
  report.potential *= energy_unit;
  report.initial_gradient_norm *= s;
  for (double& g : report.gradient_norms) g *= s;
  report.newton_trust_radius *= s;
  report.newton_reference_gradient *= s;
}

void print_progress(const DeformArguments& args, ArapMethod method, const MeshData& mesh,
                    const ConstraintSet& constraints, const ArapReport& report) {
  const Eigen::Index soft = constraints.soft.size();
  std::cerr << "deform: " << arap_method_name(method) << ", " << mesh.V.rows() << " vertices, "
            << constraints.fixed.size() << " constrained"
            << (soft > 0 ? ", " + std::to_string(soft) + " soft" : std::string()) << ", initial energy "
            << report.initial_energy << "\n";
  for (int k = 0; k < report.iterations; ++k) {
    std::cerr << "deform: iteration " << k + 1 << "/" << args.solve.max_iterations << " energy "
              << report.energies[k] << " gradient " << report.gradient_norms[k]
              << (report.accepted[k] ? " accelerated" : "") << " (local " << report.local_ms_per_iteration[k]
              << " ms, global " << report.global_ms_per_iteration[k] << " ms)\n";
  }
  std::cerr << "deform: " << (report.converged ? "converged" : "stopped") << " ("
            << arap_stop_reason_name(report.stop_reason) << ")\n";
}

nlohmann::json intrinsic_json(const ArapIntrinsicSummary& intrinsic, const std::string& boundary) {
  return {{"flips", intrinsic.flips},
          {"non_delaunay_before", intrinsic.non_delaunay_before},
          {"non_delaunay_after", intrinsic.non_delaunay_after},
          {"mollify_delta", intrinsic.mollify_delta},
          {"intrinsic_edges", intrinsic.intrinsic_edges},
          {"segments", intrinsic.segments},
          {"boundary", boundary},
          {"obtuse_boundary_before", intrinsic.obtuse_boundary_before},
          {"obtuse_boundary_after", intrinsic.obtuse_boundary_after},
          {"inserted_points", intrinsic.inserted_points}};
}

void run_deform(const DeformArguments& args) {
  check_arguments(args);
  const auto total_start = Clock::now();
  nlohmann::json j;
  j["input"] = args.mesh;
  MeshData mesh;
  ConstraintSet constraints;
  Eigen::MatrixXd forces_in_file; // 0 x 0 without --forces
  load_mesh_and_constraints(args, mesh, constraints, forces_in_file, j);
  const MeshReport check = check_mesh(mesh.V, mesh.F);
  require_usable(args, check);
  for (const auto& warning : constraints.warnings) std::cerr << "deform: warning: " << warning << "\n";
  if (!args.quiet) {
    for (const auto& warning : check.warnings)
      std::cerr << "deform: mesh warning: " << name_repair(warning, deform_repair_flag) << "\n";
  }

  set_thread_count(args.threads == 0 ? automatic_thread_count(static_cast<int>(mesh.V.rows()))
                                     : args.threads);
  ArapOptions options;
  options.method = parse_arap_method(args.method);
  options.pin_unconstrained_components = args.pin_unconstrained;
  options.intrinsic.refine_boundary = args.boundary == "refine";
  // The solve runs on the mesh divided by a power of two s that brings its coordinates near 1 (exact), so
  // that squared lengths neither overflow nor underflow at 1e+-80 and beyond; results return in file units.
  const double s = normalizing_scale(mesh.V);
  const Eigen::MatrixXd V = mesh.V / s;
  const Eigen::MatrixXd targets = constraints.targets / s;
  // A mesh in the plane z = 0 whose targets stay in it deforms in its plane, with rotations about z (a cell
  // squeezed through a reflection keeps a 2x2 rotation); targets off the plane make it a 3D deformation.
  // Soft weights need no scaling: E_ARAP and W |x - t|^2 both scale with length^2.
  const ArapSoftConstraints soft = soft_constraints_of(constraints.soft);
  const Eigen::MatrixXd soft_targets = soft_targets_of(constraints.soft) / s;
  const Eigen::MatrixXd forces =
      statics_forces(args, mesh, constraints.fixed, soft, V, options.method, s, forces_in_file);
  options.planar = (V.col(2).array() == 0.0).all() && (targets.col(2).array() == 0.0).all() &&
                   (soft_targets.rows() == 0 || (soft_targets.col(2).array() == 0.0).all()) &&
                   (forces.rows() == 0 || (forces.col(2).array() == 0.0).all());
  const ErrorContext context{args.mesh, args.repair};
  const auto precompute_start = Clock::now();
  ArapData arap = precompute_explained(V, mesh.F, constraints.fixed, soft, options, context);
  const double precompute_ms = ms_since(precompute_start);

  Eigen::MatrixXd U = V;
  ArapSolveOptions solve_options = args.solve;
  scale_length_options(solve_options, s);
  solve_options.forces = forces;
  ArapReport report;
  try {
    report = arap_solve(arap, targets, soft_targets, U, solve_options);
  } catch (const HardPointConflict& e) {
    throw InputError(hard_point_conflict_message(e, constraints.soft));
  } catch (const SolverError& e) {
    if (std::string(e.what()).find("initial guess is not finite") != std::string::npos)
      throw SolverError(
          "the ARAP energy of the constraints overflows: " + farthest_target(constraints, mesh.V) +
          ", against a mesh of bounding-box diagonal " + std::to_string(check.bbox_diagonal) +
          "; give targets at a distance comparable to the mesh");
    throw SolverError(explain_solver_error(e.what(), context));
  }
  const double max_displacement = (U - V).rowwise().norm().maxCoeff() * s; // no overflow at 1e300
  U *= s;
  to_file_units(report, s);
  if (!args.quiet) print_progress(args, options.method, mesh, constraints, report);
  if (options.method == ArapMethod::Arap) warn_about_original_energy(report, check);
  write_mesh(args.out, U, mesh.F);

  j["method"] = arap_method_name(options.method);
  j["planar"] = options.planar;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["constrained"] = constraints.fixed.size();
  j["pinned"] = arap.pinned.size();
  j["threads"] = thread_count();
  j["options"] = solve_options_json(args.solve);
  add_arap_report_json(report, j);
  // The energy of the result = arap_energy + penalty, penalty = sum_k W_k |c_k^T U - t_k|^2 (file units).
  j["energy"] = report.arap_energy + report.penalty;
  j["soft"] = soft.size();
  if (args.forces.any()) add_statics_keys(args.forces, report, j);
  j["window"] = args.solve.window; // as before "options" held it
  j["precompute_ms"] = precompute_ms;
  j["intrinsic_ms"] = arap.timings.intrinsic_ms;
  j["assembly_ms"] = arap.timings.assembly_ms;
  j["factor_ms"] = arap.timings.factor_ms;
  j["analyze_ms"] = arap.timings.analyze_ms; // overlapped with intrinsic + assembly when threads > 1
  j["factorization"] = factorization_name(arap_factorization(arap));
  j["max_displacement"] = max_displacement;
  j["bbox_diagonal"] = check.bbox_diagonal;
  j["output"] = args.out;
  j["total_ms"] = ms_since(total_start);
  if (options.method == ArapMethod::Iarap) j["intrinsic"] = intrinsic_json(arap.intrinsic, args.boundary);
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json) std::cout << text;
  if (!args.quiet) std::cerr << "deform: wrote " << args.out << "\n";
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
           sub->add_option("--constraints", args->constraints,
                           "Constraints file: 'index x y z' per line ('index x y' in the plane z = 0)")
               ->check(CLI::ExistingFile);
       auto* scenario = sub->add_option("--scenario", args->scenario, "Scenario file (JSON; see README.md)")
                            ->check(CLI::ExistingFile);
       constraints->excludes(scenario);
       sub->add_option("--method", args->method, "Energy: arap, spokes-rims or iarap")
           ->check(CLI::IsMember({"arap", "spokes-rims", "iarap"}))
           ->capture_default_str();
       sub->add_option(
              "--boundary", args->boundary,
              "iARAP on meshes with boundary: 'refine' splits boundary edges whose opposite angle is obtuse "
              "(non-negative weights, stays at rest); 'paper' is the paper's exact discretization")
           ->check(CLI::IsMember({"paper", "refine"}))
           ->capture_default_str();
       add_solve_option_flags(*sub, args->solve);
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = all hardware threads")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--out", args->out, "Output mesh (.obj .off .ply), written atomically")->required();
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_flag(
           "--repair", args->repair,
           "Repair the mesh first: weld, drop unreferenced vertices and degenerate or duplicate faces, split "
           "non-manifold edges and vertices, orient faces consistently (constraint indices are mapped)");
       sub->add_flag("--pin-unconstrained", args->pin_unconstrained,
                     "Pin one vertex of each connected component that has no constraint (else an error)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       add_external_force_options(*sub, args->forces);
       sub->callback([args] { run_deform(*args); });
     }});

} // namespace
} // namespace iarap::cli
