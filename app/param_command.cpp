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
#include "iarap/io/read_obj_textured.h"
#include "iarap/mesh/validate.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/render_uv_picture.h"
#include "iarap/param/texture_seam_charts.h"
#include "iarap/param/uv_atlas.h"
#include "iarap/param/write_uv_map.h"
#include "iarap/scene/read_constraints.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace iarap::cli {
namespace {

struct ParamArguments {
  std::string mesh, out, report, picture, pins, energy = "triangle", init, boundary = "free";
  ArapSolveOptions solve = default_param_solve_options();
  std::string charts = "auto";
  AtlasOptions atlas; // the atlas's own options (atlas.param is filled from the rest)
  int threads = 0;
  bool tolerance_given = false; // --tolerance on the command line (an atlas has its own default)
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

// The fields every param report has, one chart or an atlas: the files, the mesh's size, the threads.
nlohmann::json run_json(const ParamArguments& args, const MeshData& mesh) {
  nlohmann::json j;
  j["input"] = args.mesh;
  j["output"] = args.out;
  j["vertices"] = mesh.V.rows();
  j["faces"] = mesh.F.rows();
  j["threads"] = thread_count();
  return j;
}

nlohmann::json report_json(const ParamArguments& args, const MeshData& mesh, const ParamOptions& options,
                           const ParamReport& report) {
  nlohmann::json j = run_json(args, mesh);
  j["boundary"] = param_boundary_name(options.boundary);
  j["pins"] = options.pins.size();
  if (!args.pins.empty()) j["pins_file"] = args.pins;
  j["allow_flips"] = options.allow_flips;
  j.update(param_report_json(report));
  return j;
}

// The library's errors with the mesh's path in front, as every command names the file.
template <class Run> auto naming_the_mesh(const std::string& mesh, Run run) {
  try {
    return run();
  } catch (const TopologyError& e) {
    throw TopologyError(mesh + ": " + e.what());
  } catch (const InputError& e) {
    throw InputError(mesh + ": " + e.what());
  } catch (const SolverError& e) {
    throw SolverError(mesh + ": " + e.what());
  }
}

// With --picture: renders and writes it, and records the path and the time in the report.
template <class Render> void add_picture(const ParamArguments& args, nlohmann::json& j, Render render) {
  if (args.picture.empty()) return;
  const auto picture_start = Clock::now();
  write_png(args.picture, render());
  j["picture"] = args.picture;
  j["picture_ms"] = ms_since(picture_start);
}

// `--charts auto` flattens a topological disk as one chart (as before the atlas existed) and cuts anything
// else into charts; a mesh check_mesh cannot use goes to the atlas, which refuses it with check_mesh's words.
bool one_chart(const ParamArguments& args, const MeshData& mesh) {
  if (args.charts == "one") return true;
  if (args.charts == "keep") return false;
  const MeshReport check = check_mesh(mesh.V, mesh.F);
  return check.usable() && check.components == 1 && check.boundary_loops == 1 && check.genus == 0;
}

nlohmann::json atlas_json(const ParamArguments& args, const MeshData& mesh, const AtlasOptions& options,
                          const AtlasReport& report) {
  nlohmann::json j = run_json(args, mesh);
  j["charts_mode"] = args.charts;
  cli::add_atlas_report_json(j, options, report);
  return j;
}

// The atlas's picture: each face on its own three vertices (the charts come apart at the seams).
RgbImage atlas_picture(const MeshData& mesh, const UvAtlas& atlas) {
  std::vector<int> faces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (atlas.chart(f) >= 0) faces.push_back(static_cast<int>(f));
  const auto n = static_cast<Eigen::Index>(faces.size());
  Eigen::MatrixXd V(3 * n, 3), UV(3 * n, 2);
  Eigen::MatrixXi F(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      V.row(3 * i + k) = mesh.V.row(mesh.F(faces[static_cast<std::size_t>(i)], k));
      UV.row(3 * i + k) = atlas.corner_uv.row(3 * faces[static_cast<std::size_t>(i)] + k);
      F(i, k) = static_cast<int>(3 * i + k);
    }
  UvPictureOptions options;
  options.checker_squares = 64;
  return render_uv_picture(V, F, UV, options);
}

// What an OBJ adds to its mesh: the face lines as written and the texture coordinates (empty otherwise).
struct MeshInput {
  MeshData mesh;
  std::optional<TexturedObj> obj; // for a .obj input
};

MeshInput read_input(const std::string& path) {
  MeshInput input;
  if (lower_extension(path) != ".obj") {
    input.mesh = read_mesh(path);
    return input;
  }
  input.obj = read_obj_textured(path);
  input.mesh = input.obj->mesh;
  return input;
}

bool has_polygons(const MeshInput& input) {
  return input.obj && input.obj->polygons.size() != input.mesh.F.rows();
}

// An OBJ output of an input with polygons gets the input's face lines back (a .txt has per-vertex or
// per-triangle-corner lines as without polygons).
bool writes_polygons(const ParamArguments& args, const MeshInput& input) {
  return has_polygons(input) && lower_extension(args.out) == ".obj";
}

// `--charts keep`: the charts and layout of the file's vt, every face needing texture indices.
void keep_file_charts(const ParamArguments& args, const MeshInput& input, AtlasInput& atlas_input) {
  if (!input.obj)
    throw InputError(args.mesh +
                     ": --charts keep reads an OBJ's texture coordinates (vt); this is not an OBJ");
  const TexturedObj& obj = *input.obj;
  if (obj.TC.rows() == 0)
    throw InputError(args.mesh +
                     ": --charts keep needs the file's texture coordinates, and it has no vt lines");
  for (int p = 0; p < obj.polygons.size(); ++p)
    if (obj.polygons.texture[static_cast<std::size_t>(obj.polygons.first[static_cast<std::size_t>(p)])] < 0)
      throw InputError(args.mesh + ": --charts keep needs texture indices (i/t) on every face; face " +
                       std::to_string(p) + " (the file's f line number " + std::to_string(p + 1) +
                       ") has none");
  atlas_input.charts = texture_seam_charts(obj.mesh.F, obj.FT);
  atlas_input.corner_uv.resize(3 * obj.FT.rows(), 2);
  for (Eigen::Index f = 0; f < obj.FT.rows(); ++f)
    for (int k = 0; k < 3; ++k) atlas_input.corner_uv.row(3 * f + k) = obj.TC.row(obj.FT(f, k));
}

void write_atlas(const ParamArguments& args, const MeshInput& input, const UvAtlas& atlas) {
  if (writes_polygons(args, input))
    write_uv_atlas_polygons(args.out, input.mesh.V, input.mesh.F, atlas.corner_uv, atlas.chart,
                            input.obj->polygons);
  else
    write_uv_atlas(args.out, input.mesh.V, input.mesh.F, atlas.corner_uv);
}

void run_atlas(const ParamArguments& args, const MeshInput& input, const ParamOptions& param,
               Clock::time_point total_start) {
  const MeshData& mesh = input.mesh;
  AtlasOptions options = args.atlas;
  options.param = param;
  if (!args.tolerance_given) options.param.solve.tolerance = default_atlas_param_options().solve.tolerance;
  AtlasInput atlas_input;
  if (has_polygons(input)) atlas_input.polygon_of_face = input.obj->polygon_of_triangle;
  if (args.charts == "keep") keep_file_charts(args, input, atlas_input);
  const UvAtlas atlas =
      naming_the_mesh(args.mesh, [&] { return uv_atlas(mesh.V, mesh.F, options, atlas_input); });
  const AtlasReport& report = atlas.report;
  write_atlas(args, input, atlas);
  nlohmann::json j = atlas_json(args, mesh, options, report);
  add_picture(args, j, [&] { return atlas_picture(mesh, atlas); });
  j["total_ms"] = ms_since(total_start);
  if (!args.quiet)
    std::cerr << "param: " << report.charts.size() << " charts, distortion " << report.distortion
              << " (energy / area), " << report.flipped << " flipped triangles, packing efficiency "
              << report.packing_efficiency << ", overlap " << report.overlap_ratio << "\nparam: wrote "
              << args.out << (args.picture.empty() ? "" : " and " + args.picture) << "\n";
  const std::string text = json_text(j);
  if (!args.report.empty()) write_text_file(args.report, text);
  if (args.json) std::cout << text;
}

void run_param(const ParamArguments& args) {
  check_paths(args);
  ParamOptions options = options_of(args);
  const auto total_start = Clock::now();
  const MeshInput input = read_input(args.mesh);
  const MeshData& mesh = input.mesh;
  if (!one_chart(args, mesh)) {
    if (!args.pins.empty())
      throw CLI::ValidationError("--pins needs one chart: " + args.mesh +
                                 " is not a topological disk (use --charts one for a disk)");
    // Automatic: the charts are flattened in parallel, each on one thread (the atlas is the same on any
    // count), so from serial_vertex_threshold vertices every hardware thread.
    set_thread_count(args.threads == 0 ? automatic_thread_count(static_cast<int>(mesh.V.rows()))
                                       : args.threads);
    run_atlas(args, input, options, total_start);
    return;
  }
  if (!args.pins.empty()) options.pins = read_pins(args.pins, mesh);
  // Automatic: one thread. The per-triangle loops are serial and the solves have two columns; camelhead
  // (11.4K vertices) on the 2-core machine, 5 paired runs: 0.43-0.65 s on one thread, 0.84-0.95 s on two.
  set_thread_count(args.threads == 0 ? 1 : args.threads);
  const ParamResult result =
      naming_the_mesh(args.mesh, [&] { return arap_parameterize(mesh.V, mesh.F, options); });
  const ParamReport& report = result.report;
  if (writes_polygons(args, input)) { // the polygons as written, one vt per vertex
    Eigen::MatrixXd corner_uv(3 * mesh.F.rows(), 2);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) corner_uv.row(3 * f + k) = result.UV.row(mesh.F(f, k));
    write_uv_atlas_polygons(args.out, mesh.V, mesh.F, corner_uv, Eigen::VectorXi::Zero(mesh.F.rows()),
                            input.obj->polygons);
  } else {
    write_uv_map(args.out, mesh.V, mesh.F, result.UV);
  }
  nlohmann::json j = report_json(args, mesh, options, report);
  add_picture(args, j, [&] { return render_uv_picture(mesh.V, mesh.F, result.UV); });
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

const bool param_command_registered = register_command(
    {"param", [](CLI::App& app) {
       auto args = std::make_shared<ParamArguments>();
       auto* sub =
           app.add_subcommand("param", "Flatten a disk-like mesh into the plane: an ARAP parameterization "
                                       "(UV map), flip-free by default");
       sub->add_option("MESH", args->mesh,
                       "Input mesh (.obj .off .ply .stl); a disk is one chart, another surface an atlas")
           ->required()
           ->check(CLI::ExistingFile);
       sub->add_option(
              "--out", args->out,
              "Output: .obj (the mesh with one vt per vertex, faces a/a; an atlas: per vertex and chart; "
              "an OBJ's polygons as written) or .txt (one 'u v' per vertex; an atlas: per triangle "
              "corner), written atomically")
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
       sub->add_option("--charts", args->charts,
                       "auto: a topological disk is one chart, any other mesh is cut into disk charts and "
                       "packed into [0,1]^2; one: a single chart (the mesh must be a disk); keep: the "
                       "charts of the OBJ's own vt seams, each flattened from its vt layout when that "
                       "folds nothing, then packed")
           ->check(CLI::IsMember({"auto", "one", "keep"}))
           ->capture_default_str();
       sub->add_option("--texture-size", args->atlas.texture_size,
                       "Atlas: texels along a side of the texture")
           ->check(CLI::Range(16, 16384))
           ->capture_default_str();
       sub->add_option("--padding", args->atlas.padding, "Atlas: texels between charts")
           ->check(CLI::Range(0.0, 8192.0))
           ->capture_default_str();
       sub->add_option("--max-angle", args->atlas.max_normal_angle,
                       "Atlas: degrees a face's normal may turn from its chart's mean normal")
           ->check(CLI::Range(1.0, 180.0))
           ->capture_default_str();
       sub->add_option("--target-distortion", args->atlas.target_distortion,
                       "Atlas: split a chart whose ARAP energy / area exceeds this")
           ->check(CLI::PositiveNumber)
           ->capture_default_str();
       sub->add_option("--min-chart-faces", args->atlas.min_chart_faces,
                       "Atlas: smaller charts are merged into neighbours, and no split makes them")
           ->check(CLI::Range(1, 1 << 30))
           ->capture_default_str();
       sub->add_flag("--allow-flips", args->allow_flips,
                     "Minimize the energy alone (no barrier, no injectivity bound on the steps): triangles "
                     "may fold, as in libigl and CGAL");
       // The engine's options, as deform's (solve_option_flags.h); each accelerator stays flip-free.
       add_solve_option_flags(*sub, args->solve);
       sub->add_option(
              "--threads", args->threads,
              "Threads for the parallel loops; 0 = automatic (one chart: one thread; an atlas, whose "
              "charts are flattened in parallel: all from 10K vertices)")
           ->check(CLI::Range(0, 4096))
           ->capture_default_str();
       sub->add_option("--picture", args->picture,
                       "Also write a PNG: the UV layout over a checkerboard (flipped triangles red) beside "
                       "the mesh textured with it");
       sub->add_flag("--json", args->json, "Print the run's report as one JSON object on stdout");
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_flag("--quiet", args->quiet, "No progress lines on stderr");
       sub->callback([args, sub] {
         args->tolerance_given = sub->count("--tolerance") > 0;
         run_param(*args);
       });
     }});

} // namespace
} // namespace iarap::cli
