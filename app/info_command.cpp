// `iarap info MESH`: what check_mesh finds, and what the intrinsic Delaunay triangulation looks like.
#include "command_registry.h"
#include "common/json_text.h"
#include "mesh_report_json.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/validate.h"

#include <iostream>

namespace iarap::cli {
namespace {

struct InfoArguments {
  std::string mesh;
  bool json = false;
  bool no_intrinsic = false;
};

void print_text(const nlohmann::json& j) {
  std::cout << "file: " << j["file"].get<std::string>() << "\n";
  if (j.contains("vertices")) {
    std::cout << "vertices " << j["vertices"] << ", faces " << j["faces"] << ", components "
              << j["components"] << ", boundary loops " << j["boundary_loops"] << ", genus "
              << (j["genus"].is_null()
                      ? std::string(j["orientable"].get<bool>() ? "undefined" : "undefined (non-orientable)")
                      : j["genus"].dump())
              << ", orientable " << (j["orientable"].get<bool>() ? "yes" : "no") << "\n"
              << "bounding-box diagonal " << j["bbox_diagonal"] << "\n";
    for (const char* count :
         {"non_manifold_edges", "non_manifold_vertices", "inconsistently_oriented_edges",
          "repeated_vertex_faces", "out_of_range_indices", "non_finite_coordinates", "zero_area_faces",
          "unreferenced_vertices", "coincident_vertices", "boundary_edges", "non_delaunay_edges"}) {
      std::cout << "  " << count << ": " << j[count] << "\n";
    }
  }
  for (const auto& note : j.value("notes", nlohmann::json::array()))
    std::cout << "note: " << note.get<std::string>() << "\n";
  for (const auto& warning : j["warnings"]) std::cout << "warning: " << warning.get<std::string>() << "\n";
  for (const auto& error : j["errors"]) std::cout << "error: " << error.get<std::string>() << "\n";
  if (j.contains("intrinsic")) {
    const auto& in = j["intrinsic"];
    if (in.contains("error")) {
      std::cout << "intrinsic Delaunay: failed: " << in["error"].get<std::string>() << "\n";
    } else {
      std::cout << "intrinsic Delaunay: " << in["flips"] << " flips, non-Delaunay edges "
                << in["non_delaunay_before"] << " -> " << in["non_delaunay_after"] << ", " << in["segments"]
                << " segments (" << in["segments_per_edge"].get<double>() << " per edge, at most "
                << in["max_segments_per_edge"] << "), " << in["time_ms"].get<double>() << " ms\n";
    }
  }
  for (const auto& need : j.value("deform_needs", nlohmann::json::array())) {
    std::string methods;
    for (const auto& m : need["methods"]) methods += (methods.empty() ? "" : ", ") + m.get<std::string>();
    std::cout << "deform needs " << need["flag"].get<std::string>() << " (" << methods
              << "): " << need["why"].get<std::string>() << "\n";
  }
  if (j["usable"].get<bool>())
    std::cout << "usable for ARAP: yes\n";
  else if (j.value("deformable", false))
    std::cout << "usable for ARAP: yes, as it is (not an oriented manifold: `iarap deform` runs iARAP on its "
                 "tufted cover, original ARAP and spokes-and-rims on its own edges and faces; "
                 "docs/nonmanifold.md)\n";
  else
    std::cout << "usable for ARAP: no\n";
}

// What `iarap deform` needs beyond the defaults (deform_needs, the library's verdict), as JSON.
nlohmann::json deform_needs_json(const MeshReport& report) {
  nlohmann::json needs = nlohmann::json::array();
  for (const DeformNeed& need : deform_needs(report))
    needs.push_back({{"flag", need.flag}, {"why", need.why}, {"methods", need.methods}});
  return needs;
}

void run_info(const InfoArguments& args) {
  nlohmann::json j;
  j["file"] = args.mesh;
  bool ok = true;
  try {
    const MeshData mesh = read_mesh(args.mesh);
    const MeshReport report = check_mesh(mesh.V, mesh.F);
    j.update(mesh_report_json(report));
    j["notes"] = mesh.notes;
    j["deform_needs"] = deform_needs_json(report);
    // `deform` takes it without --repair: exit 0, though check_mesh's `usable` (a manifold, for the tools
    // that need one) stays false.
    j["deformable"] = report.deformable();
    ok = report.deformable();
    // The summary is of the input's own intrinsic triangulation, which needs an oriented manifold.
    if (report.usable() && !args.no_intrinsic) {
      try {
        const auto start = Clock::now();
        IntrinsicOptions options;
        options.keep_traces = false; // the summary reads the segments
        // On the mesh divided by a power of two (exact), as `deform` does: coordinates of 1e+-80 and beyond
        // would overflow or underflow its squared lengths.
        const IntrinsicDelaunay intrinsic =
            intrinsic_delaunay(mesh.V / normalizing_scale(mesh.V), mesh.F, options);
        const double elapsed_ms = ms_since(start);
        j["intrinsic"] = intrinsic_summary_json(intrinsic);
        j["intrinsic"]["time_ms"] = elapsed_ms;
      } catch (const Error& e) {
        j["intrinsic"] = {{"error", e.what()}};
        ok = false;
      }
    }
  } catch (const Error& e) { // unreadable: the report still says why
    j["errors"] = {e.what()};
    j["warnings"] = nlohmann::json::array();
    j["usable"] = false;
    ok = false;
  }
  if (args.json) {
    std::cout << json_text(j);
  } else {
    print_text(j);
  }
  std::cout.flush();
  if (!ok) throw InputError(args.mesh + ": not usable for ARAP (see the report above)");
}

const bool info_command_registered = register_command(
    {"info", [](CLI::App& app) {
       auto args = std::make_shared<InfoArguments>();
       auto* sub = app.add_subcommand(
           "info", "Check a mesh (topology, degeneracies, Delaunay-ness) for ARAP; "
                   "exit 0 when usable (or deformable as it is: not an oriented manifold), 1 when not or "
                   "unreadable");
       sub->add_option("MESH", args->mesh, "Mesh file (.obj .off .ply .stl)")->required();
       sub->add_flag("--json", args->json, "Print one JSON object instead of text");
       sub->add_flag("--no-intrinsic", args->no_intrinsic, "Skip the intrinsic Delaunay triangulation");
       sub->callback([args] { run_info(*args); });
     }});

} // namespace
} // namespace iarap::cli
