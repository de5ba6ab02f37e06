// `iarap deform MESH`: one ARAP deformation from a constraints or scenario file, written to a mesh file.
#include "command_registry.h"
#include "common/explain_error.h"
#include "common/json_text.h"
#include "external_force_options.h"
#include "same_file.h"
#include "solve_option_flags.h"
#include "solve_report_json.h"
#include "write_text_file.h"

#include "iarap/core/blas_library.h"
#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/io/write_tet_mesh.h"
#include "iarap/jobs/deform_job.h"
#include "iarap/jobs/volume_deform.h"
#include "iarap/mesh/validate.h"
#include "iarap/solver/arap.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

namespace iarap::cli {
namespace {

struct DeformArguments {
  std::string mesh, constraints, scenario, stiffness, rigid, method = "iarap", boundary = "refine", out,
                                                             report;
  std::string ordering = "auto";
  ArapSolveOptions solve; // the flags of solve_option_flags.h; forces are set from `forces` below
  int threads = 0;
  bool json = false, repair = false, keep_numbering = false, pin_unconstrained = false, quiet = false;
  bool volume = false;           // tetrahedralize the closed surface's inside and deform the tetrahedra
  ExternalForceArguments forces; // statics under gravity / per-vertex forces (none: the plain deformation)
};

// The mesh to deform and its constraints, read and prepared by the library's job (read_deform_scene: with
// --repair the mesh is repaired, a scenario resolved on the repaired mesh, a constraints file's indices and
// the forces and stiffness files' rows carried over; a tetrahedral mesh (.mesh .node .ele .msh) is read as
// one, its constraints per vertex and its `b` lines on its boundary faces).
DeformScene read_and_prepare(const DeformArguments& args) {
  if (args.repair && is_tet_mesh_path(args.mesh))
    throw CLI::ValidationError("--repair is for triangle meshes; " + args.mesh + " is a tetrahedral mesh");
  DeformPrepareOptions options;
  options.repair = args.repair;
  return read_deform_scene(
      {args.mesh, args.scenario, args.constraints, args.forces.forces, args.stiffness, args.rigid}, options);
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
  if (is_tet_mesh_path(args.mesh) && is_tet_mesh_output_path(args.out))
    check_output_path(args.out); // the tetrahedra, as MEDIT
  else
    check_mesh_output_path(args.out);
  if (!args.report.empty()) check_output_path(args.report);
}

// A tetrahedral mesh's result: the tetrahedra (.mesh) or the boundary surface (.obj .off .ply, with the
// tet mesh's vertex numbering: interior vertices stay in the file, used by no face). Report keys: the
// tetrahedra, the negative cotangent weights (obtuse dihedral angles, kept) and the volume ratio
// sum of signed volumes after / before.
void write_tet_result(const DeformArguments& args, const DeformScene& scene, const DeformResult& result,
                      nlohmann::json& j) {
  if (is_tet_mesh_output_path(args.out))
    write_tet_mesh(args.out, result.U, scene.tets);
  else
    write_mesh(args.out, result.U, scene.mesh.F);
  const double ratio =
      tet_signed_volumes(result.U, scene.tets).sum() / tet_signed_volumes(scene.mesh.V, scene.tets).sum();
  j["tetrahedra"] = scene.tets.rows();
  j["negative_weights"] = result.data.negative_weights;
  j["volume_ratio"] = ratio;
  if (!args.quiet)
    std::cerr << "deform: " << scene.tets.rows() << " tetrahedra, volume after / before " << ratio << "\n";
}

// Refuses a mesh ARAP cannot deform; one that is only not an oriented manifold is deformed as it is.
void require_usable(const DeformArguments& args, const MeshReport& check) {
  if (check.deformable()) return;
  std::string message = args.mesh + (args.repair ? ": mesh not usable for ARAP after --repair:"
                                                 : ": mesh not usable for ARAP:");
  for (const auto& error : check.errors) message += "\n  " + name_repair(error, deform_repair_flag);
  throw TopologyError(message + (args.repair ? "\n(numbers refer to the repaired mesh; `iarap info " +
                                                   args.mesh + "` reports the file as it is)"
                                             : "\n(run `iarap info " + args.mesh + "` for the full report)"));
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
          {"inserted_points", intrinsic.inserted_points},
          {"tufted_cover", intrinsic.tufted_cover},
          {"cover_vertices", intrinsic.cover_vertices}};
}

// The job's solve with the library's errors told in the tool's words (explain_solver_error).
DeformResult solve_explained(const DeformArguments& args, const DeformScene& scene,
                             const ArapOptions& options) {
  StaticForces forces;
  forces.present = args.forces.any();
  forces.gravity = args.forces.gravity_vector();
  forces.density = args.forces.density;
  const ErrorContext context{args.mesh, args.repair};
  try {
    return solve_deform(scene, options, args.solve, forces);
  } catch (const SolverError& e) {
    throw SolverError(explain_solver_error(e.what(), context));
  } catch (const TopologyError& e) {
    throw TopologyError(explain_solver_error(e.what(), context));
  }
}

// The deformed mesh (U on scene's surface), or with --keep-numbering the input's vertices and faces at
// their copies' mean. For a closed surface the report's volume_ratio is the enclosed volume after / before.
void write_result(const DeformArguments& args, const DeformScene& scene, const Eigen::MatrixXd& U,
                  nlohmann::json& j) {
  if (scene.check.boundary_edges == 0)
    j["volume_ratio"] = enclosed_volume(U, scene.mesh.F) / enclosed_volume(scene.mesh.V, scene.mesh.F);
  if (!args.keep_numbering) return write_mesh(args.out, U, scene.mesh.F);
  double spread = 0.0;
  write_mesh(args.out, in_input_numbering(scene, U, &spread), scene.input.F);
  j["keep_numbering"] = true;
  j["copies_spread"] = spread;
  if (!args.quiet && spread > 0)
    std::cerr << "deform: --keep-numbering: the copies of split vertices lie up to " << spread
              << " from their mean (" << spread / scene.check.bbox_diagonal << " of the diagonal)\n";
}

// --volume: the surface (the first rows of the tet mesh's result) written with its own faces; report keys
// volume_ratio (the surface's enclosed volume after / before), tetrahedra, interior_points, the tetrahedra's
// own volume ratio and the tetrahedralization's time.
void write_volume_result(const DeformArguments& args, const DeformScene& surface, const DeformScene& scene,
                         const DeformResult& result, double tetrahedralize_ms, nlohmann::json& j) {
  const Eigen::Index n = surface.mesh.V.rows();
  write_result(args, surface, result.U.topRows(n), j);
  j["volume"] = true;
  j["tetrahedra"] = scene.tets.rows();
  j["interior_points"] = scene.mesh.V.rows() - n;
  j["tet_volume_ratio"] =
      tet_signed_volumes(result.U, scene.tets).sum() / tet_signed_volumes(scene.mesh.V, scene.tets).sum();
  j["tetrahedralize_ms"] = tetrahedralize_ms;
  if (!args.quiet)
    std::cerr << "deform: --volume: " << scene.tets.rows() << " tetrahedra (" << scene.mesh.V.rows() - n
              << " interior points, TetGen " << tetrahedralize_ms << " ms), enclosed volume after / before "
              << j["volume_ratio"].get<double>() << "\n";
}

void run_deform(const DeformArguments& args) {
  check_arguments(args);
  const auto total_start = Clock::now();
  nlohmann::json j;
  j["input"] = args.mesh;
  const DeformScene surface = read_and_prepare(args);
  require_usable(args, surface.check);
  // --volume: the surface's inside tetrahedralized (TetGen, run as a program), the surface its first rows.
  double tetrahedralize_ms = 0.0;
  const DeformScene volume =
      args.volume ? timed(tetrahedralize_ms, [&] { return volume_scene(surface); }) : DeformScene();
  const DeformScene& scene = args.volume ? volume : surface;
  if (args.repair) j["repair"] = surface.repairs;
  if (!args.stiffness.empty()) j["stiffness"] = args.stiffness;
  if (!args.rigid.empty()) j["rigid_groups"] = scene.rigid_groups.size();
  const MeshData& mesh = surface.mesh; // the keys and messages count the surface (--volume: not the tets)
  const ConstraintSet& constraints = scene.constraints;
  for (const auto& warning : constraints.warnings) std::cerr << "deform: warning: " << warning << "\n";
  if (!args.quiet) {
    for (const auto& warning : surface.check.warnings)
      std::cerr << "deform: mesh warning: " << name_repair(warning, deform_repair_flag) << "\n";
    // Deformable: each error only says "not an oriented manifold".
    const std::string how = args.method == "iarap" ? "iARAP on the tufted cover" : "on the input's own edges";
    for (const auto& error : scene.check.errors)
      std::cerr << "deform: mesh warning: " << name_repair(error, deform_repair_flag)
                << " (deformed as it is: " << how << ", docs/nonmanifold.md)\n";
  }

  set_thread_count(args.threads == 0 ? automatic_thread_count(static_cast<int>(mesh.V.rows()))
                                     : args.threads);
  ArapOptions options;
  options.method = parse_arap_method(args.method);
  options.pin_unconstrained_components = args.pin_unconstrained;
  options.intrinsic.refine_boundary = args.boundary == "refine";
  options.ordering = parse_fill_ordering(args.ordering);
  const DeformResult result = solve_explained(args, scene, options);
  const ArapReport& report = result.report;
  const ArapData& arap = result.data;
  if (!args.quiet) print_progress(args, options.method, mesh, constraints, report);
  if (options.method == ArapMethod::Arap) warn_about_original_energy(report, scene.check);
  if (args.volume)
    write_volume_result(args, surface, scene, result, tetrahedralize_ms, j);
  else if (scene.tets.rows() > 0)
    write_tet_result(args, scene, result, j);
  else
    write_result(args, scene, result.U, j);

  j["method"] = arap_method_name(options.method);
  j["planar"] = result.planar;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["constrained"] = constraints.fixed.size();
  j["pinned"] = arap.pinned.size();
  j["min_weight"] = arap.min_weight;
  j["threads"] = thread_count();
  j["options"] = solve_options_json(args.solve);
  add_arap_report_json(report, j);
  // The energy of the result = arap_energy + penalty, penalty = sum_k W_k |c_k^T U - t_k|^2 (file units).
  j["energy"] = report.arap_energy + report.penalty;
  j["soft"] = constraints.soft.size();
  if (args.forces.any()) add_statics_keys(args.forces, report, j);
  j["window"] = args.solve.window; // as before "options" held it
  j["precompute_ms"] = result.precompute_ms;
  j["intrinsic_ms"] = arap.timings.intrinsic_ms;
  j["assembly_ms"] = arap.timings.assembly_ms;
  j["factor_ms"] = arap.timings.factor_ms;
  j["analyze_ms"] = arap.timings.analyze_ms; // overlapped with intrinsic + assembly when threads > 1
  j["factorization"] = factorization_name(arap_factorization(arap));
  j["ordering"] = fill_ordering_name(arap.solver.used_ordering());
  j["blas"] = blas_library_name();
  j["memory"] = memory_json(arap);
  j["max_displacement"] = result.max_displacement;
  j["bbox_diagonal"] = scene.check.bbox_diagonal;
  j["output"] = args.out;
  j["total_ms"] = ms_since(total_start);
  if (options.method == ArapMethod::Iarap && scene.tets.rows() == 0)
    j["intrinsic"] = intrinsic_json(arap.intrinsic, args.boundary);
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json) std::cout << text;
  if (!args.quiet) std::cerr << "deform: wrote " << args.out << "\n";
}

const bool deform_command_registered = register_command(
    {"deform", [](CLI::App& app) {
       auto args = std::make_shared<DeformArguments>();
       auto* sub = app.add_subcommand(
           "deform", "Deform a mesh with ARAP (original, spokes-and-rims or iARAP), "
                     "starting from the rest shape with constrained vertices at their targets");
       sub->add_option(
              "MESH", args->mesh,
              "Input mesh (.obj .off .ply .stl; tetrahedral: .mesh .node .ele .msh, volumetric ARAP)")
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
       sub->add_option(
              "--ordering", args->ordering,
              "CHOLMOD's fill-reducing ordering: auto (amd below 1M free vertices, metis from there), amd "
              "(faster analysis) or metis (a 25-40% smaller factor on meshes of millions of vertices; "
              "docs/performance.md)")
           ->check(CLI::IsMember({"auto", "amd", "metis"}))
           ->capture_default_str();
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = all hardware threads")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--out", args->out,
                       "Output mesh (.obj .off .ply; .mesh keeps a tetrahedral input's tetrahedra), written "
                       "atomically")
           ->required();
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       auto* repair_flag = sub->add_flag(
           "--repair", args->repair,
           "Repair the mesh first: weld, drop unreferenced vertices and degenerate or duplicate faces, split "
           "non-manifold edges and vertices, orient faces consistently (constraint indices are mapped)");
       sub->add_flag(
              "--keep-numbering", args->keep_numbering,
              "With --repair: write the input's vertices (each at the mean of its copies) and faces, so "
              "that the output keys on the input's numbering; the report gives the copies' spread")
           ->needs(repair_flag);
       sub->add_flag("--pin-unconstrained", args->pin_unconstrained,
                     "Pin one vertex of each connected component that has no constraint (else an error)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       add_external_force_options(*sub, args->forces);
       sub->add_option(
              "--stiffness", args->stiffness,
              "Stiffness file: 'index s' per line, s > 0 multiplies the energy of that vertex's cell "
              "(others 1): a stiffer region bends and stretches less")
           ->check(CLI::ExistingFile);
       sub->add_flag(
           "--volume", args->volume,
           "Deform the closed surface as a solid: its inside is tetrahedralized by TetGen (the "
           "'tetgen' program, Debian package tetgen), the tetrahedra deformed by tet ARAP under the "
           "surface's constraints; the output is the surface with its own vertices and faces");
       sub->add_option("--rigid", args->rigid,
                       "Rigid parts: one group per line, 'i j k ...' (at least 2 vertices each): each group "
                       "moves as one rigid body (6 degrees of freedom each; every accelerator)")
           ->check(CLI::ExistingFile);
       sub->callback([args] { run_deform(*args); });
     }});

} // namespace
} // namespace iarap::cli
