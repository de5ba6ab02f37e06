// `iarap param MESH --out OUT.obj`: an ARAP parameterization (UV map) of a disk-like mesh, flip-free by
// default, written as an OBJ with texture coordinates or as `u v` lines, and on request pictured in a PNG.
#include "command_registry.h"
#include "common/json_text.h"
#include "common/param_report_json.h"
#include "same_file.h"
#include "solve_option_flags.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/render_uv_picture.h"
#include "iarap/param/write_uv_map.h"
#include "iarap/scene/read_constraints.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

namespace iarap::cli {
namespace {

struct ParamArguments {
  std::string mesh, out, report, picture, pins, energy = "triangle", init, boundary = "free";
  ArapSolveOptions solve = default_param_solve_options();
  int threads = 0;
  bool allow_flips = false, json = false, quiet = false;
};

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void check_paths(const ParamArguments& args) {
  if (same_file(args.out, args.mesh))
    throw CLI::ValidationError("--out " + args.out + " is the input mesh; refusing to overwrite it");
  if (!args.pins.empty() && same_file(args.out, args.pins))
    throw CLI::ValidationError("--out " + args.out + " is the pins file; refusing to overwrite it");
  if (!args.report.empty() && (same_file(args.report, args.mesh) || same_file(args.report, args.out) ||
                               (!args.pins.empty() && same_file(args.report, args.pins))))
    throw CLI::ValidationError("--report " + args.report + " is the input mesh or the output");
  const std::string extension = lower_extension(args.out);
  if (extension != ".obj" && extension != ".txt")
    throw CLI::ValidationError("--out " + args.out +
                               ": a UV map is written as .obj (mesh with vt) or .txt (u v)");
  if (!args.picture.empty()) {
    if (same_file(args.picture, args.mesh) || same_file(args.picture, args.out) ||
        (!args.report.empty() && same_file(args.picture, args.report)))
      throw CLI::ValidationError("--picture " + args.picture +
                                 " is the input mesh, the output or the report");
    if (lower_extension(args.picture) != ".png")
      throw CLI::ValidationError("--picture " + args.picture + ": the picture is written as .png");
  }
  check_output_path(args.out);
  if (!args.report.empty()) check_output_path(args.report);
  if (!args.picture.empty()) check_output_path(args.picture);
}

ParamOptions options_of(const ParamArguments& args) {
  ParamOptions options;
  options.energy = parse_param_energy(args.energy);
  options.boundary = parse_param_boundary(args.boundary);
  options.init = args.init.empty() ? default_param_init(options.boundary) : parse_param_init(args.init);
  if (options.boundary == ParamBoundary::Circle && options.init == ParamInit::Lscm)
    throw CLI::ValidationError("--boundary circle needs --init tutte or harmonic (lscm has a free boundary)");
  options.allow_flips = args.allow_flips;
  options.solve = args.solve;
  return options;
}

// The pins file: constraints-file lines 'index u v' (hard vertex targets in the plane; 'index u v 0' too).
// Soft lines and a third coordinate other than 0 are refused, naming the line.
UvPins read_pins(const std::string& path, const MeshData& mesh) {
  const ConstraintSet set =
      read_constraints(path, static_cast<int>(mesh.V.rows()), static_cast<int>(mesh.F.rows()));
  if (set.soft.size() > 0)
    throw InputError(set.soft.origins.front() +
                     ": UV pins are hard: 'index u v' (weights and points on faces are not pins)");
  for (Eigen::Index k = 0; k < set.fixed.size(); ++k)
    if (set.targets(k, 2) != 0)
      throw InputError(set.origins[static_cast<std::size_t>(k)] +
                       ": a UV pin has two coordinates, 'index u v'");
  UvPins pins;
  pins.vertices = set.fixed;
  pins.uv = set.targets.leftCols(2);
  return pins;
}

nlohmann::json report_json(const ParamArguments& args, const MeshData& mesh, const ParamOptions& options,
                           const ParamReport& report) {
  nlohmann::json j;
  j["input"] = args.mesh;
  j["output"] = args.out;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["boundary"] = param_boundary_name(options.boundary);
  j["pins"] = options.pins.size();
  if (!args.pins.empty()) j["pins_file"] = args.pins;
  j["allow_flips"] = options.allow_flips;
  j["threads"] = thread_count();
  j.update(param_report_json(report));
  return j;
}

void run_param(const ParamArguments& args) {
  check_paths(args);
  ParamOptions options = options_of(args);
  const auto total_start = Clock::now();
  const MeshData mesh = read_mesh(args.mesh);
  if (!args.pins.empty()) options.pins = read_pins(args.pins, mesh);
  // Automatic: one thread. The per-triangle loops are serial and the solves have two columns; camelhead
  // (11.4K vertices) on the 2-core machine, 5 paired runs: 0.43-0.65 s on one thread, 0.84-0.95 s on two.
  set_thread_count(args.threads == 0 ? 1 : args.threads);
  ParamResult result;
  try {
    result = arap_parameterize(mesh.V, mesh.F, options);
  } catch (const TopologyError& e) {
    throw TopologyError(args.mesh + ": " + e.what());
  } catch (const InputError& e) {
    throw InputError(args.mesh + ": " + e.what());
  } catch (const SolverError& e) {
    throw SolverError(args.mesh + ": " + e.what());
  }
  const ParamReport& report = result.report;
  write_uv_map(args.out, mesh.V, mesh.F, result.UV);
  nlohmann::json j = report_json(args, mesh, options, report);
  if (!args.picture.empty()) {
    const auto picture_start = Clock::now();
    write_png(args.picture, render_uv_picture(mesh.V, mesh.F, result.UV));
    j["picture"] = args.picture;
    j["picture_ms"] = ms_since(picture_start);
  }
  j["total_ms"] = ms_since(total_start);
  if (!args.quiet) {
    if (report.init_fallback)
      std::cerr << "param: the " << param_init_name(report.requested_init) << " map flips "
                << report.init_flipped << " triangles; starting from Tutte's map (injective) instead\n";
    std::cerr << "param: " << report.solve.iterations << " iterations ("
              << arap_accelerator_name(report.solve.accelerator) << ", stopped by "
              << arap_stop_reason_name(report.solve.stop_reason) << ")"
              << ", energy " << report.distortion.energy << " (at best scale "
              << report.distortion.scaled_energy << "), " << report.distortion.flipped
              << " flipped triangles, min det J " << report.distortion.min_det_J << "\n";
    std::cerr << "param: wrote " << args.out << (args.picture.empty() ? "" : " and " + args.picture) << "\n";
  }
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json) std::cout << text;
}

const bool registered = register_command(
    {"param", [](CLI::App& app) {
       auto args = std::make_shared<ParamArguments>();
       auto* sub =
           app.add_subcommand("param", "Flatten a disk-like mesh into the plane: an ARAP parameterization "
                                       "(UV map), flip-free by default");
       sub->add_option("MESH", args->mesh, "Input mesh (.obj .off .ply .stl), a topological disk")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option(
              "--out", args->out,
              "Output: .obj (the mesh with one vt per vertex, faces a/a) or .txt (one 'u v' per vertex), "
              "written atomically")
           ->required();
       sub->add_option(
              "--energy", args->energy,
              "Energy: triangle (Liu et al. 2008's per-triangle ARAP, as libigl and CGAL), or per vertex "
              "with a 2x2 rotation per flattened cell: arap (cotan edges) or iarap (intrinsic Delaunay "
              "segments)")
           ->check(CLI::IsMember({"triangle", "arap", "iarap"}))
           ->capture_default_str();
       sub->add_option(
              "--init", args->init,
              "Initial map: lscm (free boundary), tutte or harmonic (boundary on a circle); default lscm, "
              "harmonic with --boundary circle")
           ->check(CLI::IsMember({"lscm", "tutte", "harmonic"}));
       sub->add_option("--boundary", args->boundary,
                       "free: the boundary moves; circle: held on a circle of the surface's area")
           ->check(CLI::IsMember({"free", "circle"}))
           ->capture_default_str();
       sub->add_option("--pins", args->pins,
                       "Vertices held at UV positions: lines 'index u v' (0-based; '#' comments). Free "
                       "boundary: they replace the default pin (two or more: LSCM start with them held); "
                       "circle: inner vertices, circle centred at 0 with radius sqrt(area / pi)")
           ->check(CLI::ExistingFile);
       sub->add_flag("--allow-flips", args->allow_flips,
                     "Minimize the energy alone (no barrier, no injectivity bound on the steps): triangles "
                     "may fold, as in libigl and CGAL");
       // The engine's options, as deform's (solve_option_flags.h); each accelerator stays flip-free.
       add_solve_option_flags(*sub, args->solve);
       sub->add_option("--threads", args->threads, "Threads for the parallel loops; 0 = automatic (one)")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--picture", args->picture,
                       "Also write a PNG: the UV layout over a checkerboard (flipped triangles red) beside "
                       "the mesh textured with it");
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       sub->callback([args] { run_param(*args); });
     }});

} // namespace
} // namespace iarap::cli
