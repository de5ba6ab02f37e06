// `iarap repair MESH --out FILE [--map FILE] [--report FILE] [--json]`: repair_mesh as a job of its own
// (issue 43), the repair `deform --repair` runs before its solve, written out with the vertex map so that
// data keyed on the input's vertices can follow it.
#include "command_registry.h"
#include "common/explain_error.h"
#include "common/json_text.h"
#include "same_file.h"
#include "write_text_file.h"

#include "iarap/core/errors.h"
#include "iarap/io/check_output_path.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iostream>
#include <memory>
#include <utility>
#include <vector>

namespace iarap::cli {
namespace {

struct RepairArguments {
  std::string mesh, out, map, report;
  bool json = false;
};

void check_paths(const RepairArguments& args) {
  if (same_file(args.out, args.mesh))
    throw CLI::ValidationError("--out " + args.out + " is the input mesh; refusing to overwrite it");
  if (!args.map.empty() && (same_file(args.map, args.mesh) || same_file(args.map, args.out)))
    throw CLI::ValidationError("--map " + args.map + " is the input or output mesh");
  if (!args.report.empty() && (same_file(args.report, args.mesh) || same_file(args.report, args.out) ||
                               (!args.map.empty() && same_file(args.report, args.map))))
    throw CLI::ValidationError("--report " + args.report + " is the input mesh, the output or the map");
  // Before the repair: a bad output path fails now, and nothing is written.
  check_mesh_output_path(args.out);
  if (!args.map.empty()) check_output_path(args.map);
  if (!args.report.empty()) check_output_path(args.report);
}

// The vertex map: a line `OLD NEW` per vertex of the file (NEW -1: removed; a welded vertex gets the vertex
// it was welded onto), then `OLD NEW` for each copy a split added, all in the order of OLD.
std::string vertex_map_text(const RepairResult& repaired) {
  std::vector<std::pair<int, int>> pairs;
  for (Eigen::Index o = 0; o < repaired.old_to_new.size(); ++o)
    pairs.emplace_back(static_cast<int>(o), repaired.old_to_new(o));
  for (Eigen::Index n = 0; n < repaired.new_to_old.size(); ++n) {
    const int old_index = repaired.new_to_old(n);
    if (repaired.old_to_new(old_index) != n) pairs.emplace_back(old_index, static_cast<int>(n)); // a copy
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string text =
      "# iarap repair vertex map: OLD NEW per line (NEW -1: removed; a split vertex has a line "
      "per copy)\n";
  for (const auto& [old_index, new_index] : pairs)
    text += std::to_string(old_index) + " " + std::to_string(new_index) + "\n";
  return text;
}

nlohmann::json counts_json(const RepairCounts& c) {
  nlohmann::json j = nlohmann::json::object();
  visit_repair_counts(c, [&j](const char* name, int value) { j[name] = value; });
  return j;
}

void print_text(const nlohmann::json& j) {
  std::cout << j["input"].get<std::string>() << ": " << j["vertices_before"] << " vertices, "
            << j["faces_before"] << " faces -> " << j["vertices"] << " vertices, " << j["faces"]
            << " faces\n";
  if (j["actions"].empty()) std::cout << "nothing to repair: the mesh is written unchanged\n";
  for (const auto& action : j["actions"]) std::cout << "  " << action.get<std::string>() << "\n";
  for (const auto& warning : j["warnings"]) std::cout << "warning: " << warning.get<std::string>() << "\n";
  for (const auto& note : j["notes"]) std::cout << "note: " << note.get<std::string>() << "\n";
  std::cout << "wrote " << j["output"].get<std::string>()
            << (j.contains("map") ? " and " + j["map"].get<std::string>() : std::string()) << "\n";
}

void run_repair(const RepairArguments& args) {
  check_paths(args);
  const MeshData mesh = read_mesh(args.mesh);
  for (const auto& note : mesh.notes) std::cerr << "iarap: " << args.mesh << ": " << note << "\n";
  RepairOptions options; // as `deform --repair`
  options.remove_zero_area = true;
  const RepairResult repaired = repair_mesh(mesh.V, mesh.F, options);
  const MeshReport check = check_mesh(repaired.V, repaired.F);
  if (!check.usable()) { // what repair cannot fix (a Moebius strip, non-finite coordinates): write nothing
    std::string message = args.mesh + ": still not usable for ARAP after the repair (numbers refer to the "
                                      "repaired mesh); nothing written:";
    for (const auto& error : check.errors) message += "\n  " + name_repair(error, "`iarap repair`");
    throw TopologyError(message);
  }
  write_mesh(args.out, repaired.V, repaired.F);
  if (!args.map.empty()) write_text_file(args.map, vertex_map_text(repaired));

  nlohmann::json j;
  j["input"] = args.mesh;
  j["output"] = args.out;
  if (!args.map.empty()) j["map"] = args.map;
  j["vertices_before"] = mesh.V.rows();
  j["faces_before"] = mesh.F.rows();
  j["vertices"] = repaired.V.rows();
  j["faces"] = repaired.F.rows();
  j["actions"] = repaired.actions;
  j["counts"] = counts_json(repaired.counts);
  j["warnings"] = name_repair(check.warnings, "`iarap repair`");
  j["notes"] = nlohmann::json::array();
  if (const int copies = repaired.counts.vertex_copies; copies > 0) // check_mesh cannot tell them from seams
    j["notes"].push_back(
        (copies == 1 ? std::string("the copy of a split vertex sits")
                     : std::to_string(copies) + " copies of split vertices sit") +
        " exactly at its vertex's position, by design: `info` and `deform` report coincident "
        "vertices there, and welding them (`deform --repair`) splits them again");
  if (!args.report.empty()) write_text_file(args.report, json_text(j));
  if (args.json)
    std::cout << json_text(j);
  else
    print_text(j);
}

const bool repair_command_registered = register_command(
    {"repair", [](CLI::App& app) {
       auto args = std::make_shared<RepairArguments>();
       auto* sub = app.add_subcommand(
           "repair",
           "Repair a mesh as `deform --repair` does (weld, drop degenerate and duplicate faces, "
           "split non-manifold edges and vertices, orient, drop unreferenced vertices) and write it");
       sub->add_option("MESH", args->mesh, "Mesh file (.obj .off .ply .stl)")->required();
       sub->add_option("--out", args->out, "The repaired mesh (.obj .off .ply), written atomically")
           ->required();
       sub->add_option("--report", args->report, "Also write the JSON report to this file (atomically)");
       sub->add_option("--map", args->map,
                       "Also write the vertex map: `OLD NEW` per line, NEW -1 for a removed vertex");
       sub->add_flag("--json", args->json, "Print the report as one JSON object instead of text");
       sub->callback([args] { run_repair(*args); });
     }});

} // namespace
} // namespace iarap::cli
