// End-to-end tests of `iarap repair` (issue 43): the repaired mesh is written and usable, the vertex map
// sends every vertex of the file to a vertex of the output at the same position, a clean mesh comes back
// unchanged, paths are checked before anything is read, and a mesh repair cannot fix is refused with
// nothing written.
#include "app/cli_runner.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/mesh/validate.h"
#include "mesh/small_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;

// Two closed tetrahedra touching at vertex 0 (a non-manifold vertex), one face of the second reversed, a
// copy of vertex 1 (vertex 7) used by one face in place of it, and a vertex no face uses (vertex 8).
const char* const pinched =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\nv 1 0 0\nv 5 5 5\n"
    "f 1 3 2\nf 1 8 4\nf 1 4 3\nf 2 3 4\n"
    "f 1 6 5\nf 1 7 5\nf 1 6 7\nf 5 7 6\n";

// OLD -> the NEW vertices of the map file (comments skipped).
std::map<int, std::vector<int>> read_map(const fs::path& path) {
  std::map<int, std::vector<int>> map;
  std::istringstream lines(read_file(path));
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    int old_index = 0, new_index = 0;
    EXPECT_TRUE(static_cast<bool>(words >> old_index >> new_index)) << line;
    map[old_index].push_back(new_index);
  }
  return map;
}

TEST(RepairCli, RepairsWritesAndMapsEveryVertex) {
  const auto dir = iarap::test::temp_dir("cli_repair_command");
  write_file(dir / "pinched.obj", pinched);
  const iarap::MeshData input = iarap::read_mesh((dir / "pinched.obj").string());
  ASSERT_FALSE(iarap::check_mesh(input.V, input.F).usable()); // as it is, deform refuses it

  const CliRun run =
      iarap_cli("repair '" + (dir / "pinched.obj").string() + "' --out '" + (dir / "o.off").string() +
                "' --map '" + (dir / "map.txt").string() + "' --json");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json report = parse_json(run);
  EXPECT_EQ(report["vertices_before"], 9);
  EXPECT_EQ(report["counts"]["welded_vertices"], 1);
  EXPECT_EQ(report["counts"]["split_vertices"], 1);
  EXPECT_EQ(report["counts"]["flipped_faces"], 1);
  EXPECT_EQ(report["counts"]["unreferenced_vertices"], 1);
  EXPECT_EQ(report["actions"].size(), 4u) << report["actions"];

  const iarap::MeshData output = iarap::read_mesh((dir / "o.off").string());
  EXPECT_EQ(output.V.rows(), report["vertices"].get<int>());
  EXPECT_TRUE(iarap::check_mesh(output.V, output.F).usable());
  // The map, checked against the positions: every vertex of the file is named, a kept one lands on a vertex
  // at its position, and every vertex of the output comes from exactly one line.
  const auto map = read_map(dir / "map.txt");
  ASSERT_EQ(map.size(), 9u);
  EXPECT_EQ(map.at(8), std::vector<int>{-1}); // unreferenced: removed
  EXPECT_EQ(map.at(7), map.at(1));            // welded onto vertex 1
  EXPECT_EQ(map.at(0).size(), 2u);            // split: two copies
  std::multiset<int> reached;
  for (const auto& [old_index, targets] : map)
    for (int new_index : targets) {
      if (new_index < 0) continue;
      ASSERT_LT(new_index, output.V.rows());
      EXPECT_EQ(output.V.row(new_index), input.V.row(old_index)) << old_index << " -> " << new_index;
      if (old_index != 7) reached.insert(new_index); // 7 shares vertex 1's line target
    }
  for (int v = 0; v < output.V.rows(); ++v) EXPECT_EQ(reached.count(v), 1u) << v;

  // The repaired mesh deforms without --repair.
  write_file(dir / "c.txt", std::to_string(map.at(1)[0]) + " 1 0 0\n" + std::to_string(map.at(4)[0]) +
                                " -1 0 0\n" + std::to_string(map.at(0)[0]) + " 0 0 0.5\n");
  EXPECT_EQ(iarap_cli("deform '" + (dir / "o.off").string() + "' --constraints '" + (dir / "c.txt").string() +
                      "' --out '" + (dir / "d.off").string() + "' --quiet --pin-unconstrained")
                .code,
            0);
  fs::remove_all(dir);
}

TEST(RepairCli, TextReportSaysWhatChanged) {
  const auto dir = iarap::test::temp_dir("cli_repair_text");
  write_file(dir / "pinched.obj", pinched);
  const CliRun run =
      iarap_cli("repair '" + (dir / "pinched.obj").string() + "' --out '" + (dir / "o.obj").string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("9 vertices, 8 faces -> "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("reversed 1 face"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("note: the copy of a split vertex sits exactly at its vertex's position"),
            std::string::npos)
      << run.out;
  // A clean mesh comes back as it was.
  const std::string clean_mesh = iarap::test::data_path("bunny.off");
  const CliRun clean = iarap_cli("repair '" + clean_mesh + "' --out '" + (dir / "bunny.off").string() + "'");
  ASSERT_EQ(clean.code, 0) << clean.out;
  EXPECT_NE(clean.out.find("nothing to repair"), std::string::npos) << clean.out;
  const iarap::MeshData before = iarap::read_mesh(clean_mesh),
                        after = iarap::read_mesh((dir / "bunny.off").string());
  EXPECT_EQ(after.V, before.V);
  EXPECT_EQ(after.F, before.F);
  fs::remove_all(dir);
}

TEST(RepairCli, BadPathsAndUnrepairableMeshesWriteNothing) {
  const auto dir = iarap::test::temp_dir("cli_repair_refused");
  write_file(dir / "pinched.obj", pinched);
  const std::string mesh = " '" + (dir / "pinched.obj").string() + "'";
  EXPECT_EQ(iarap_cli("repair" + mesh).code, 2);                               // no --out
  EXPECT_EQ(iarap_cli("repair" + mesh + " --out" + mesh).code, 2);             // the input itself
  EXPECT_EQ(iarap_cli("repair" + mesh + " --out o.obj --map" + mesh).code, 2); // the map over the input
  const CliRun folder =
      iarap_cli("repair" + mesh + " --out '" + (dir / "none" / "o.obj").string() + "'", true);
  EXPECT_EQ(folder.code, 1);
  EXPECT_NE(folder.out.find("none"), std::string::npos) << folder.out;
  const CliRun extension = iarap_cli("repair" + mesh + " --out '" + (dir / "o.stl").string() + "'", true);
  EXPECT_EQ(extension.code, 1) << extension.out;

  const iarap::test::SmallMesh strip = iarap::test::moebius_strip();
  iarap::write_mesh((dir / "moebius.off").string(), strip.V, strip.F);
  const CliRun moebius =
      iarap_cli("repair '" + (dir / "moebius.off").string() + "' --out '" + (dir / "o.obj").string() +
                    "' --map '" + (dir / "m.txt").string() + "'",
                true);
  EXPECT_EQ(moebius.code, 1);
  EXPECT_NE(moebius.out.find("still not usable for ARAP after the repair"), std::string::npos) << moebius.out;
  EXPECT_NE(moebius.out.find("non-orientable"), std::string::npos) << moebius.out;
  EXPECT_FALSE(fs::exists(dir / "o.obj"));
  EXPECT_FALSE(fs::exists(dir / "m.txt"));
  fs::remove_all(dir);
}

} // namespace
