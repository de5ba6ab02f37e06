// End-to-end tests of issue 20: what a new user's meshes and typos did to the tool (exit codes, messages
// that name the problem and the fix, output only after success, extreme scales).
#include "app/cli_runner.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "intrinsic/mesh_generators.h"
#include "mesh/small_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;

// A closed cone of 6 x 4 quads split in two: small enough that every method solves in milliseconds.
struct Fixture {
  fs::path dir;
  fs::path mesh;
  fs::path scenario;
};

Fixture fixture(const std::string& tag, double scale = 1.0) {
  Fixture f;
  f.dir = iarap::test::temp_dir("robust_" + tag);
  const iarap::test::TestMesh cone = iarap::test::closed_cone(8, 4, 1.5);
  f.mesh = f.dir / "cone.off";
  iarap::write_mesh(f.mesh.string(), cone.V * scale, cone.F);
  f.scenario = f.dir / "scene.json";
  write_file(f.scenario, R"({"fixed": {"bottom": 0.2, "axis": "z"},
    "handles": [{"vertices": {"top": 0.2, "axis": "z"}, "translate_relative": [0.1, 0, 0]}]})");
  return f;
}

std::string deform_args(const Fixture& f, const std::string& extra) {
  return "deform '" + f.mesh.string() + "' --scenario '" + f.scenario.string() + "' --quiet --iterations 5 " +
         extra;
}

} // namespace

// Item 4: a bad --out is found before the mesh is even read (the solve took 8.5 s on nefertiti first).
TEST(CliRobustness, BadOutputPathFailsBeforeTheSolve) {
  const Fixture f = fixture("out");
  CliRun run = iarap_cli(deform_args(f, "--out '" + (f.dir / "result.xyz").string() + "'"), true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("unsupported mesh extension '.xyz'"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("iteration"), std::string::npos) << "the solve ran: " << run.out;
  run = iarap_cli(deform_args(f, "--out '" + (f.dir / "missing" / "result.obj").string() + "'"), true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("does not exist; create it first"), std::string::npos) << run.out;
  run = iarap_cli(deform_args(f, "--out '" + f.dir.string() + "'"), true);
  EXPECT_EQ(run.code, 1);
  run = iarap_cli(deform_args(f, "--out '" + (f.dir / "ok.obj").string() + "' --report '" +
                                     (f.dir / "missing" / "r.json").string() + "'"),
                  true);
  EXPECT_EQ(run.code, 1);
  EXPECT_FALSE(fs::exists(f.dir / "ok.obj")) << "the mesh was written although the run failed";
}

// Item 4: a mesh path that is not valid UTF-8 (Linux names are bytes): deform succeeds and its JSON is
// valid (the byte becomes U+FFFD); info --json too. Before: output written, then exit 1 with
// json.exception.type_error.316.
TEST(CliRobustness, NonUtf8PathsGiveValidJson) {
  const Fixture f = fixture("utf8");
  const fs::path odd = f.dir / "bun\xff.off";
  fs::copy_file(f.mesh, odd, fs::copy_options::overwrite_existing); // a reused pid finds its old folder
  const fs::path out = f.dir / "out.obj";
  CliRun run = iarap_cli("deform '" + odd.string() + "' --scenario '" + f.scenario.string() +
                         "' --quiet --iterations 3 --json --out '" + out.string() + "'");
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_TRUE(parse_json(run).contains("energies"));
  EXPECT_TRUE(fs::exists(out));
  run = iarap_cli("info --json --no-intrinsic '" + odd.string() + "'");
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_EQ(parse_json(run).value("file", ""), f.dir.string() + "/bun\xef\xbf\xbd.off");
}

// Item 5: --tolerance nan and inf are usage errors (exit 2) in plain words, not a 309-digit range. A
// negative tolerance turns the energy rule off (solve_option_fields.h), as in the library.
TEST(CliRobustness, NonFiniteToleranceIsAUsageError) {
  const Fixture f = fixture("tolerance");
  for (const char* value : {"nan", "inf", "1e999"}) {
    const CliRun run = iarap_cli(
        deform_args(f, std::string("--tolerance ") + value + " --out '" + (f.dir / "o.obj").string() + "'"),
        true);
    EXPECT_EQ(run.code, 2) << value << ": " << run.out;
    EXPECT_NE(run.out.find("tolerance must be a finite number; got"), std::string::npos) << run.out;
    EXPECT_LT(run.out.size(), 400u) << run.out;
  }
}

// Item 5: a folder given as a mesh, and a number beyond double in a scenario.
TEST(CliRobustness, FolderAsMeshAndHugeScenarioNumberAreNamed) {
  const Fixture f = fixture("folder");
  fs::create_directories(f.dir / "meshes.obj");
  CliRun run = iarap_cli("info '" + (f.dir / "meshes.obj").string() + "'", true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("is a folder, not a mesh file"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("basic_string"), std::string::npos) << run.out;

  const fs::path scenario = f.dir / "huge.json";
  write_file(scenario,
             "{\"fixed\": [0],\n \"handles\": [{\"vertices\": [1], \"translate\": [1e400, 0, 0]}]}");
  run = iarap_cli("deform '" + f.mesh.string() + "' --scenario '" + scenario.string() + "' --out '" +
                      (f.dir / "o.obj").string() + "'",
                  true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find(scenario.string() + ":2: number 1e400 is beyond the range of a double"),
            std::string::npos)
      << run.out;
}

// Item 5: a target so far away that the energy overflows names the vertex and the handle that moved it.
TEST(CliRobustness, OverflowingTargetNamesItsHandle) {
  const Fixture f = fixture("far");
  const fs::path scenario = f.dir / "far.json";
  write_file(scenario, R"({"fixed": [0], "handles": [{"vertices": [5], "translate": [1e300, 0, 0]}]})");
  const CliRun run = iarap_cli("deform '" + f.mesh.string() + "' --scenario '" + scenario.string() +
                                   "' --out '" + (f.dir / "o.obj").string() + "' --quiet",
                               true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("the target of vertex 5"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("$.handles[0]"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(f.dir / "o.obj"));
}

// Item 5: an unconstrained part names --pin-unconstrained, not the library's option; a vertex used by no face
// (a scan's stray point) is no such part: it is kept where it is (issue 33).
TEST(CliRobustness, UnconstrainedPartNamesTheFlags) {
  const Fixture f = fixture("pin");
  iarap::MeshData cone = iarap::read_mesh(f.mesh.string());
  iarap::MeshData mesh = cone;
  const auto n = mesh.V.rows();
  mesh.V.conservativeResize(n + 4, 3); // a triangle of its own, far from the cone, then a stray point
  mesh.V.row(n) << 5, 0, 0.75;         // mid-height: neither the fixed bottom nor the handle's top selects it
  mesh.V.row(n + 1) << 6, 0, 0.75;
  mesh.V.row(n + 2) << 5, 1, 0.75;
  mesh.F.conservativeResize(mesh.F.rows() + 1, 3);
  mesh.F.row(mesh.F.rows() - 1) << static_cast<int>(n), static_cast<int>(n + 1), static_cast<int>(n + 2);
  mesh.V.row(n + 3) << 0.1, 0.1, 0.75;
  iarap::write_mesh(f.mesh.string(), mesh.V, mesh.F);
  CliRun run = iarap_cli(deform_args(f, "--out '" + (f.dir / "o.obj").string() + "'"), true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("--pin-unconstrained"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("pin_unconstrained_components"), std::string::npos) << run.out;
  // The cone with the stray point alone deforms; the point is written back where it was.
  cone.V.conservativeResize(cone.V.rows() + 1, 3);
  cone.V.row(cone.V.rows() - 1) << 0.1, 0.1, 0.75;
  iarap::write_mesh(f.mesh.string(), cone.V, cone.F);
  run = iarap_cli(deform_args(f, "--out '" + (f.dir / "kept.obj").string() + "'"), true);
  ASSERT_EQ(run.code, 0) << run.out;
  const iarap::MeshData kept = iarap::read_mesh((f.dir / "kept.obj").string());
  ASSERT_EQ(kept.V.rows(), cone.V.rows());
  EXPECT_EQ(kept.V.bottomRows(1), cone.V.bottomRows(1));
  // info warns about the stray point.
  run = iarap_cli("info --no-intrinsic '" + f.mesh.string() + "'");
  EXPECT_EQ(run.code, 0);
  // The library's warning names repair_mesh; the tool names its flag instead (issue 36).
  EXPECT_NE(run.out.find("first: vertex 34; `iarap deform --repair` removes them"), std::string::npos)
      << run.out;
  EXPECT_EQ(run.out.find("RepairOptions"), std::string::npos) << run.out;
  // --repair drops it and the run succeeds.
  run = iarap_cli(deform_args(f, "--repair --out '" + (f.dir / "o.obj").string() + "'"), true);
  EXPECT_EQ(run.code, 0) << run.out;
}

// Item 7: a box region that catches the stray vertex: with --repair the scenario is resolved on the repaired
// mesh, so it never selects it (before: --repair always failed, "constrained vertex ... was removed").
TEST(CliRobustness, RegionsAreResolvedOnTheRepairedMesh) {
  const Fixture f = fixture("regions");
  iarap::MeshData mesh = iarap::read_mesh(f.mesh.string());
  mesh.V.conservativeResize(mesh.V.rows() + 1, 3);
  mesh.V.row(mesh.V.rows() - 1) << 0.0, 0.0, -0.5; // below the cone: inside the "bottom" slab
  iarap::write_mesh(f.mesh.string(), mesh.V, mesh.F);
  const CliRun run = iarap_cli(deform_args(f, "--repair --json --out '" + (f.dir / "o.obj").string() + "'"));
  EXPECT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j.value("vertices", 0), mesh.V.rows() - 1);
}

// Item 2: the same mesh at 1e+-150 deforms like at size 1 (before: every method failed beyond 1e+-80),
// displacements scaling with it. Relative agreement 1e-9: the scaled solve is the same computation up to
// the power-of-two normalisation (exact) and the scale's own rounding (1e-16).
TEST(CliRobustness, ExtremeScalesDeformLikeUnitScale) {
  for (const char* method : {"arap", "iarap"}) {
    const Fixture unit = fixture(std::string("unit_") + method);
    const CliRun base = iarap_cli(deform_args(unit, std::string("--json --method ") + method + " --out '" +
                                                        (unit.dir / "o.obj").string() + "'"));
    ASSERT_EQ(base.code, 0) << base.out;
    const double reference = parse_json(base).value("max_displacement", 0.0);
    ASSERT_GT(reference, 0);
    for (double scale : {1e150, 1e-150}) {
      const Fixture f = fixture(std::string("scaled_") + method, scale);
      const CliRun run = iarap_cli(deform_args(f, std::string("--json --method ") + method + " --out '" +
                                                      (f.dir / "o.obj").string() + "'"));
      ASSERT_EQ(run.code, 0) << method << " at " << scale << ": " << run.out;
      EXPECT_NEAR(parse_json(run).value("max_displacement", 0.0) / scale, reference, 1e-9 * reference)
          << method << " at " << scale;
    }
  }
}

// Item 4: bench keeps every usable mesh's results when one mesh is unusable, and exits 1 at the end.
TEST(CliRobustness, BenchKeepsResultsBesideAFailingMesh) {
  const Fixture f = fixture("bench");
  const fs::path broken = f.dir / "broken.off";
  write_file(broken, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  const CliRun run = iarap_cli("bench --json --methods arap --iterations 1 '" + broken.string() + "' '" +
                               f.mesh.string() + "'");
  EXPECT_EQ(run.code, 1);
  const nlohmann::json j = parse_json(run);
  ASSERT_EQ(j["results"].size(), 2u) << run.out;
  EXPECT_TRUE(j["results"][0].contains("error"));
  EXPECT_NE(j["results"][0]["error"].get<std::string>().find("broken.off:6"), std::string::npos);
  EXPECT_FALSE(j["results"][1].contains("error"));
  EXPECT_GT(j["results"][1].value("iteration_ms", -1.0), 0.0);
}

// Item 9: original ARAP on a mesh with many negative cotangent weights warns and points to --method iarap.
TEST(CliRobustness, OriginalArapWarnsAboutNegativeWeights) {
  const Fixture f = fixture("negative");
  // A flat grid whose interior diagonals are flipped at random: many obtuse angle pairs (non-Delaunay edges).
  iarap::test::TestMesh grid = iarap::test::planar_grid(8, 0.0);
  iarap::test::random_planar_flips(grid, 40);
  iarap::write_mesh(f.mesh.string(), grid.V, grid.F);
  write_file(
      f.scenario,
      R"({"fixed": {"bottom": 0.2}, "handles": [{"vertices": {"top": 0.2}, "translate_relative": [0, 0, 0.2]}]})");
  CliRun run = iarap_cli(deform_args(f, "--method arap --out '" + (f.dir / "o.obj").string() + "'"), true);
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("negative cotangent weights"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("--method iarap"), std::string::npos) << run.out;
  run = iarap_cli(deform_args(f, "--method iarap --out '" + (f.dir / "o.obj").string() + "'"), true);
  EXPECT_EQ(run.out.find("negative cotangent weights"), std::string::npos) << run.out;
}

// Issue 47, item 1: two cubes touching at a corner (a vertex where two closed fans meet) deform without
// --repair with every method, the output with the input's 15 vertices; the report gives min_weight and,
// for iARAP, that it ran on the tufted cover (32 cover vertices: each cube's front and back).
TEST(CliRobustness, NonManifoldVertexDeformsWithoutRepair) {
  const Fixture f = fixture("cubes");
  const iarap::test::SmallMesh cubes = iarap::test::two_cubes_at_a_corner();
  iarap::write_mesh(f.mesh.string(), cubes.V, cubes.F);
  write_file(f.scenario, R"({"fixed": {"bottom": 0.2, "axis": "z"},
    "handles": [{"vertices": {"top": 0.2, "axis": "z"}, "translate_relative": [0.1, 0, 0]}]})");
  for (const std::string method : {"iarap", "arap", "spokes-rims"}) {
    const fs::path out = f.dir / ("o_" + method + ".obj");
    const CliRun run =
        iarap_cli(deform_args(f, "--method " + method + " --json --out '" + out.string() + "'"));
    ASSERT_EQ(run.code, 0) << run.out;
    const nlohmann::json j = parse_json(run);
    EXPECT_EQ(j["vertices"].get<int>(), 15) << method;
    EXPECT_TRUE(j.contains("min_weight")) << method;
    EXPECT_EQ(iarap::read_mesh(out.string()).V.rows(), 15) << method;
    if (method == "iarap") {
      EXPECT_TRUE(j["intrinsic"]["tufted_cover"].get<bool>());
      EXPECT_EQ(j["intrinsic"]["cover_vertices"].get<int>(), 32);
      EXPECT_GE(j["min_weight"].get<double>(), -1e-12);
    }
  }
  // Without --quiet the tool says why it runs on a mesh check_mesh calls not usable.
  const std::string args = "deform '" + f.mesh.string() + "' --scenario '" + f.scenario.string() +
                           "' --iterations 5 --out '" + (f.dir / "o.obj").string() + "'";
  const CliRun run = iarap_cli(args, true);
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("non-manifold (a closed fan of faces touches another fan there)"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("deformed as it is"), std::string::npos) << run.out;
}
