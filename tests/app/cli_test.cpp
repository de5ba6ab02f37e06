// End-to-end tests of the iarap tool: exit codes (0 ok, 1 runtime error, 2 usage error), JSON output,
// output files. They run the built binary (IARAP_CLI_PATH) through the shell.
#include "app/cli_runner.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "iarap/scene/read_constraints.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <utility>
#include <vector>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;
using nlohmann::json;

const std::string bunny = iarap::test::data_path("bunny.off");

TEST(Cli, HelpOnEachCommandExitsZero) {
  for (const char* command :
       {"--help", "info --help", "deform --help", "bench --help", "param --help", "repair --help"}) {
    const CliRun run = iarap_cli(command);
    EXPECT_EQ(run.code, 0) << command;
    EXPECT_NE(run.out.find("Usage"), std::string::npos) << command << ":\n" << run.out;
  }
}

TEST(Cli, NoOrUnknownCommandIsUsageError) {
  EXPECT_EQ(iarap_cli("").code, 2);
  // An unknown word is named, with the commands there are (not CLI11's "A subcommand is required").
  const std::pair<std::string, std::string> cases[] = {
      {"reticulate", "reticulate"}, {"frobnicate x.off", "frobnicate"}, {"--help frobnicate", "frobnicate"}};
  for (const auto& [args, word] : cases) {
    const CliRun run = iarap_cli(args, true);
    EXPECT_EQ(run.code, 2) << args;
    EXPECT_NE(
        run.out.find("unknown subcommand '" + word + "'; expected one of: batch, bench, deform, info, "),
        std::string::npos)
        << run.out;
    EXPECT_EQ(run.out.find("A subcommand is required"), std::string::npos) << run.out;
  }
}

TEST(Cli, InfoJsonOnBunny) {
  const CliRun run = iarap_cli("info --json '" + bunny + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  EXPECT_EQ(j["file"], bunny);
  EXPECT_EQ(j["vertices"], 3485);
  EXPECT_EQ(j["faces"], 6966);
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["boundary_loops"], 0);
  EXPECT_EQ(j["genus"], 0);
  EXPECT_EQ(j["non_manifold_edges"], 0);
  EXPECT_EQ(j["non_manifold_vertices"], 0);
  EXPECT_EQ(j["zero_area_faces"], 0);
  EXPECT_EQ(j["unreferenced_vertices"], 0);
  EXPECT_GT(j["non_delaunay_edges"].get<int>(), 0); // shared/meshes/README: 9% non-Delaunay
  EXPECT_GT(j["bbox_diagonal"].get<double>(), 0);
  EXPECT_TRUE(j["errors"].empty());
  EXPECT_TRUE(j["warnings"].is_array());
  const json& in = j["intrinsic"];
  EXPECT_EQ(in["non_delaunay_before"], j["non_delaunay_edges"]);
  EXPECT_EQ(in["non_delaunay_after"], 0);
  EXPECT_GT(in["flips"].get<long>(), 0);
  EXPECT_GT(in["segments"].get<long>(), in["intrinsic_edges"].get<long>()); // flipped edges cross input edges
  EXPECT_GT(in["segments_per_edge"].get<double>(), 1.0);
  EXPECT_GE(in["max_segments_per_edge"].get<int>(), 2);
  EXPECT_GE(in["time_ms"].get<double>(), 0.0);

  const json skipped = parse_json(iarap_cli("info --json --no-intrinsic '" + bunny + "'"));
  EXPECT_FALSE(skipped.contains("intrinsic"));
  const CliRun text = iarap_cli("info '" + bunny + "'");
  EXPECT_EQ(text.code, 0);
  EXPECT_NE(text.out.find("usable for ARAP: yes"), std::string::npos) << text.out;
}

TEST(Cli, InfoOnUnreadableOrMissingMeshExitsOneAndSaysWhy) {
  const auto dir = iarap::test::temp_dir("cli_info_bad");
  write_file(dir / "garbage.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n");
  for (const fs::path& path : {dir / "garbage.off", dir / "missing.off"}) {
    const CliRun run = iarap_cli("info --json '" + path.string() + "'");
    EXPECT_EQ(run.code, 1) << path;
    const json j = parse_json(run);
    EXPECT_EQ(j["file"], path.string());
    ASSERT_EQ(j["errors"].size(), 1u) << run.out;
    EXPECT_NE(j["errors"][0].get<std::string>().find(path.string()), std::string::npos) << run.out;
  }
  fs::remove_all(dir);
}

// Not a manifold: check_mesh's `usable` is false, but `deform` takes it as it is (the tufted cover, issue
// 47): `deformable`, exit 0.
TEST(Cli, InfoOnNonManifoldCubeSaysDeformable) {
  IARAP_SHARED_MESH_OR_SKIP(cube, "cube_40k.obj");
  const CliRun run = iarap_cli("info --json '" + cube + "'");
  EXPECT_EQ(run.code, 0);
  const json j = parse_json(run);
  EXPECT_GT(j["non_manifold_edges"].get<int>(), 0);
  EXPECT_TRUE(j["genus"].is_null());
  EXPECT_FALSE(j["usable"].get<bool>());
  EXPECT_TRUE(j["deformable"].get<bool>());
  EXPECT_FALSE(j.contains("intrinsic")); // the input's own triangulation needs an oriented manifold
  bool named = false;
  for (const auto& error : j["errors"])
    named = named || error.get<std::string>().find("non-manifold") != std::string::npos;
  EXPECT_TRUE(named) << j["errors"].dump();
}

TEST(Cli, DeformWithConstraintsFile) {
  const auto dir = iarap::test::temp_dir("cli_deform");
  const std::string constraints = iarap::test::data_path("bunny_constraints.txt");
  const fs::path out = dir / "out.obj";
  const CliRun run =
      iarap_cli("deform '" + bunny + "' --constraints '" + constraints +
                "' --method arap --iterations 5 --threads 1 --json --quiet --out '" + out.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  for (const char* key : {"method", "iterations", "energies", "precompute_ms", "intrinsic_ms", "factor_ms",
                          "local_ms", "global_ms", "output", "converged", "max_displacement"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["method"], "arap");
  EXPECT_EQ(j["output"], out.string());
  EXPECT_LE(j["iterations"].get<int>(), 5);
  EXPECT_EQ(j["energies"].size(), j["iterations"].get<std::size_t>());
  EXPECT_EQ(j["intrinsic_ms"], 0.0); // original ARAP builds no intrinsic triangulation
  EXPECT_EQ(j["threads"], 1);

  const auto result = iarap::read_mesh(out.string());
  const auto rest = iarap::read_mesh(bunny);
  ASSERT_EQ(result.V.rows(), 3485);
  ASSERT_EQ(result.F, rest.F);
  // Constrained vertices land on their targets: the solver sets them exactly and OBJ keeps 17 digits.
  const auto c = iarap::read_constraints(constraints, 3485);
  double worst = 0;
  for (Eigen::Index k = 0; k < c.fixed.size(); ++k) {
    worst = std::max(worst, (result.V.row(c.fixed(k)) - c.targets.row(k)).norm());
  }
  EXPECT_EQ(worst, 0.0);
  // The handle moved by 10% of the diagonal, so some vertex moved at least that far.
  const double diagonal = j["bbox_diagonal"].get<double>();
  EXPECT_NEAR(j["max_displacement"].get<double>(), (result.V - rest.V).rowwise().norm().maxCoeff(),
              1e-15 * diagonal);
  EXPECT_GE(j["max_displacement"].get<double>(), 0.1 * diagonal * (1 - 1e-12));
  fs::remove_all(dir);
}

// A mesh in the plane z = 0 with targets in it ('index x y' lines) deforms in its plane: the report says so
// and the output's z is exactly 0; a target lifted off the plane makes it a 3D deformation.
TEST(Cli, PlanarMeshDeformsInItsPlane) {
  const auto dir = iarap::test::temp_dir("cli_planar");
  std::ostringstream off;
  const int n = 6; // (n + 1)^2 vertices on [0, 1]^2, two triangles per square
  off << "OFF\n" << (n + 1) * (n + 1) << " " << 2 * n * n << " 0\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) off << double(i) / n << " " << double(j) / n << " 0\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      off << "3 " << a << " " << b << " " << d << "\n3 " << a << " " << d << " " << c << "\n";
    }
  write_file(dir / "grid.off", off.str());
  std::ostringstream planar, lifted;
  for (int j = 0; j <= n; ++j) {
    planar << j * (n + 1) << " 0 " << double(j) / n << "\n";             // left column at rest
    planar << j * (n + 1) + n << " 1.2 " << double(j) / n + 0.1 << "\n"; // right column moved in plane
    lifted << j * (n + 1) << " 0 " << double(j) / n << " 0\n";
    lifted << j * (n + 1) + n << " 1 " << double(j) / n << " 0.3\n";
  }
  write_file(dir / "planar.txt", planar.str());
  write_file(dir / "lifted.txt", lifted.str());
  for (const char* method : {"arap", "spokes-rims", "iarap"}) {
    const CliRun run = iarap_cli("deform '" + (dir / "grid.off").string() + "' --constraints '" +
                                 (dir / "planar.txt").string() + "' --method " + method +
                                 " --json --quiet --out '" + (dir / "out.off").string() + "'");
    ASSERT_EQ(run.code, 0) << run.out;
    EXPECT_EQ(parse_json(run)["planar"], true) << method;
    const auto result = iarap::read_mesh((dir / "out.off").string());
    EXPECT_TRUE((result.V.col(2).array() == 0.0).all()) << method;
    EXPECT_GT(result.V.col(0).maxCoeff(), 1.1) << method; // the right column moved
  }
  const CliRun lifted_run = iarap_cli("deform '" + (dir / "grid.off").string() + "' --constraints '" +
                                      (dir / "lifted.txt").string() + "' --json --quiet --out '" +
                                      (dir / "lifted.off").string() + "'");
  ASSERT_EQ(lifted_run.code, 0) << lifted_run.out;
  EXPECT_EQ(parse_json(lifted_run)["planar"], false);
  EXPECT_GT(iarap::read_mesh((dir / "lifted.off").string()).V.col(2).maxCoeff(), 0.2);
  fs::remove_all(dir);
}

// Issue 32: soft vertices ('i x y z w') and a soft face point ('b f b0 b1 b2 x y z w') in a constraints file;
// the report splits the energy of the result into arap_energy + penalty, and a bad line exits 1 naming it.
TEST(Cli, DeformWithSoftConstraints) {
  const auto dir = iarap::test::temp_dir("cli_soft");
  const auto rest = iarap::read_mesh(bunny);
  const double lo = rest.V.col(1).minCoeff(), hi = rest.V.col(1).maxCoeff();
  const fs::path constraints = dir / "soft.txt", bad = dir / "bad.txt", out = dir / "out.obj";
  {
    std::ofstream file(constraints);
    file.precision(17);
    for (Eigen::Index v = 0; v < rest.V.rows(); ++v) {
      const double t = (rest.V(v, 1) - lo) / (hi - lo);
      if (t <= 0.1) file << v << " " << rest.V(v, 0) << " " << rest.V(v, 1) << " " << rest.V(v, 2) << "\n";
      if (t >= 0.9)
        file << v << " " << rest.V(v, 0) + 0.01 << " " << rest.V(v, 1) << " " << rest.V(v, 2) << " 2\n";
    }
    file << "b 100 0.2 0.3 0.5 0 0 0 0.001\n";
    std::ofstream(bad) << "0 0 0 0\nb 100 0.2 0.3 0.6 0 0 0 1\n";
  }
  const CliRun run = iarap_cli("deform '" + bunny + "' --constraints '" + constraints.string() +
                               "' --iterations 30 --threads 1 --json --quiet --out '" + out.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  EXPECT_GT(j["soft"].get<int>(), 10);
  const double penalty = j["penalty"].get<double>(), arap = j["arap_energy"].get<double>();
  EXPECT_GT(penalty, 0.0);
  EXPECT_GT(arap, 0.0);
  EXPECT_EQ(j["energy"].get<double>(), arap + penalty);
  EXPECT_NEAR(j["energies"].back().get<double>(), arap + penalty, 1e-15 * (arap + penalty));
  const CliRun failed = iarap_cli("deform '" + bunny + "' --constraints '" + bad.string() +
                                      "' --quiet --out '" + out.string() + "'",
                                  true);
  EXPECT_EQ(failed.code, 1) << failed.out;
  EXPECT_NE(failed.out.find(bad.string() + ":2: barycentric coordinates sum to 1.1"), std::string::npos)
      << failed.out;
  fs::remove_all(dir);
}

// Hard points on faces ('b f b0 b1 b2 x y z', no weight): the bottom held by vertices, points on the top
// faces moved; the written mesh has every point on its target to 1e-9 of the diagonal (the bound;
// the OBJ is written with 17 digits), and a point that contradicts an earlier one exits 1 naming both lines.
TEST(Cli, DeformWithHardFacePoints) {
  const auto dir = iarap::test::temp_dir("cli_hard_points");
  const auto rest = iarap::read_mesh(bunny);
  const double lo = rest.V.col(1).minCoeff(), hi = rest.V.col(1).maxCoeff();
  const double diagonal = (rest.V.colwise().maxCoeff() - rest.V.colwise().minCoeff()).norm();
  const fs::path constraints = dir / "hard.txt", bad = dir / "bad.txt", out = dir / "out.obj";
  std::vector<Eigen::Index> faces;
  std::vector<Eigen::RowVector3d> targets;
  const Eigen::RowVector3d B(0.2, 0.3, 0.5);
  {
    std::ofstream file(constraints);
    file.precision(17);
    for (Eigen::Index v = 0; v < rest.V.rows(); ++v)
      if ((rest.V(v, 1) - lo) / (hi - lo) <= 0.1)
        file << v << " " << rest.V(v, 0) << " " << rest.V(v, 1) << " " << rest.V(v, 2) << "\n";
    for (Eigen::Index f = 0; f < rest.F.rows(); f += 25) {
      Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
      for (int j = 0; j < 3; ++j) p += B(j) * rest.V.row(rest.F(f, j));
      if ((p.y() - lo) / (hi - lo) < 0.9) continue;
      p.x() += 0.05 * diagonal;
      faces.push_back(f);
      targets.push_back(p);
      file << "b " << f << " 0.2 0.3 0.5 " << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    std::ofstream bad_file(bad);
    bad_file.precision(17);
    bad_file << "0 0 0 0\nb 7 0.2 0.3 0.5 0 0 0\nb 8 1 0 0 1 1 1\nb 7 0.2 0.3 0.5 0 0 1\n";
  }
  ASSERT_GT(faces.size(), 3u);
  const CliRun run = iarap_cli("deform '" + bunny + "' --constraints '" + constraints.string() +
                               "' --iterations 100 --threads 1 --json --quiet --out '" + out.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  EXPECT_EQ(j["soft"].get<size_t>(), faces.size());
  EXPECT_EQ(j["penalty"].get<double>(), 0.0);
  const auto result = iarap::read_mesh(out.string());
  double off = 0.0;
  for (size_t k = 0; k < faces.size(); ++k) {
    Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
    for (int c = 0; c < 3; ++c) p += B(c) * result.V.row(rest.F(faces[k], c));
    off = std::max(off, (p - targets[k]).norm());
  }
  std::printf("%zu hard points, largest distance to a target %.3g of the diagonal\n", faces.size(),
              off / diagonal);
  EXPECT_LT(off, 1e-9 * diagonal);
  EXPECT_GT((result.V - rest.V).rowwise().norm().maxCoeff(), 0.02 * diagonal);
  const CliRun failed = iarap_cli("deform '" + bunny + "' --constraints '" + bad.string() +
                                      "' --quiet --out '" + (dir / "bad.obj").string() + "'",
                                  true);
  EXPECT_EQ(failed.code, 1) << failed.out;
  EXPECT_NE(failed.out.find(bad.string() + ":4: this hard point on a face contradicts the one at " +
                            bad.string() + ":2"),
            std::string::npos)
      << failed.out;
  EXPECT_FALSE(fs::exists(dir / "bad.obj"));
  fs::remove_all(dir);
}

TEST(Cli, DeformWithScenarioWritesReport) {
  const auto dir = iarap::test::temp_dir("cli_scenario");
  const fs::path out = dir / "bunny_iarap.off";
  const fs::path report = dir / "report.json";
  const CliRun run =
      iarap_cli("deform '" + bunny + "' --scenario '" + iarap::test::data_path("bunny_scenario.json") +
                "' --method iarap --iterations 3 --tolerance 0 --out '" + out.string() + "' --report '" +
                report.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_TRUE(run.out.empty()) << "no --json: nothing on stdout, got:\n" << run.out;
  const json j = json::parse(read_file(report));
  EXPECT_EQ(j["method"], "iarap");
  EXPECT_EQ(j["iterations"], 3);
  EXPECT_GT(j["intrinsic_ms"].get<double>(), 0.0);
  EXPECT_GT(j["intrinsic"]["flips"].get<long>(), 0);
  const auto& energies = j["energies"];
  ASSERT_EQ(energies.size(), 3u);
  EXPECT_LE(energies[2].get<double>(), energies[0].get<double>()); // iARAP descends
  EXPECT_EQ(iarap::read_mesh(out.string()).V.rows(), 3485);
  fs::remove_all(dir);
}

// The accelerators from the command line: the report says which ran, how many back-substitutions it made
// (Newton: one per conjugate-gradient step, so more than one per iteration) and stops on the gradient rule.
TEST(Cli, DeformAcceleratorsReportTheirWork) {
  const auto dir = iarap::test::temp_dir("cli_accel");
  const std::string scenario = iarap::test::data_path("bunny_scenario.json");
  for (const std::string accel : {"none", "anderson", "lbfgs", "newton"}) {
    const fs::path out = dir / (accel + ".off");
    const std::string limit = accel == "none" ? "20" : "400"; // plain needs thousands for 1e-8
    const CliRun run = iarap_cli("deform '" + bunny + "' --scenario '" + scenario +
                                 "' --method spokes-rims --accel " + accel + " --iterations " + limit +
                                 " --tolerance 0 --grad-tol 1e-8 --json --out '" + out.string() + "'");
    ASSERT_EQ(run.code, 0) << run.out;
    const json j = parse_json(run);
    EXPECT_EQ(j["accelerator"], accel);
    const int iterations = j["iterations"].get<int>();
    EXPECT_GE(j["solves"].get<int>(), iterations) << accel;
    if (accel == "newton") {
      EXPECT_GT(j["solves"].get<int>(), iterations);
    }
    if (accel != "none") {
      EXPECT_TRUE(j["converged"].get<bool>()) << accel;
      EXPECT_LE(j["gradient_norms"].back().get<double>(), 1e-8 * j["initial_gradient_norm"].get<double>());
    }
  }
  fs::remove_all(dir);
}

TEST(Cli, DeformRefusesToOverwriteItsInput) {
  const auto dir = iarap::test::temp_dir("cli_overwrite");
  fs::copy_file(bunny, dir / "bunny.off");
  const std::string before = read_file(dir / "bunny.off");
  const std::string scenario = iarap::test::data_path("bunny_scenario.json");
  for (const std::string& out : {(dir / "bunny.off").string(), (dir / "." / "bunny.off").string()}) {
    const CliRun run = iarap_cli("deform '" + (dir / "bunny.off").string() + "' --scenario '" + scenario +
                                     "' --out '" + out + "'",
                                 true);
    EXPECT_EQ(run.code, 2) << run.out;
    EXPECT_NE(run.out.find("refusing to overwrite"), std::string::npos) << run.out;
  }
  EXPECT_EQ(read_file(dir / "bunny.off"), before);
  fs::remove_all(dir);
}

TEST(Cli, BadArgumentsAreUsageErrors) {
  const auto dir = iarap::test::temp_dir("cli_usage");
  const std::string scenario = " --scenario '" + iarap::test::data_path("bunny_scenario.json") + "'";
  const std::string out = " --out '" + (dir / "o.off").string() + "'";
  const std::string mesh = " '" + bunny + "'";
  for (const std::string& args : std::vector<std::string>{
           "deform" + mesh + scenario + out + " --iterations -1",
           "deform" + mesh + scenario + out + " --method fast-arap",
           "deform" + mesh + scenario + out + " --threads -2",
           "deform" + mesh + scenario + out + " --tolerance inf",
           "deform" + mesh + scenario + out + " --iterations many",
           "deform" + mesh + scenario + out + " --accel fast",
           "deform" + mesh + scenario + out + " --window -1",
           "deform" + mesh + scenario + out + " --grad-tol nan",
           "deform '/nonexistent/mesh.off'" + scenario + out,
           "deform" + mesh + " --scenario /nonexistent/s.json" + out,
           "deform" + mesh + out,
           "deform" + mesh + scenario,
           "deform" + mesh + scenario + " --constraints '" + iarap::test::data_path("bunny_constraints.txt") +
               "'" + out,
           "bench" + mesh + " --methods arap,fast",
           "bench" + mesh + " --iterations 0",
           "bench /nonexistent/mesh.off",
           "info",
       }) {
    const CliRun run = iarap_cli(args, true);
    EXPECT_EQ(run.code, 2) << args << "\n" << run.out;
  }
  EXPECT_FALSE(fs::exists(dir / "o.off"));
  fs::remove_all(dir);
}

TEST(Cli, RuntimeErrorsExitOne) {
  const auto dir = iarap::test::temp_dir("cli_runtime");
  write_file(dir / "garbage.off", "OFF\n3 1 0\n0 0 0\n");
  write_file(dir / "far.txt", "0 0 0 0\n# next is out of range\n3485 1 2 3\n");
  const std::string out = " --out '" + (dir / "o.off").string() + "'";
  const std::string scenario = " --scenario '" + iarap::test::data_path("bunny_scenario.json") + "'";
  const CliRun unreadable =
      iarap_cli("deform '" + (dir / "garbage.off").string() + "'" + scenario + out, true);
  EXPECT_EQ(unreadable.code, 1) << unreadable.out;
  EXPECT_NE(unreadable.out.find("garbage.off"), std::string::npos) << unreadable.out;
  const CliRun far =
      iarap_cli("deform '" + bunny + "' --constraints '" + (dir / "far.txt").string() + "'" + out, true);
  EXPECT_EQ(far.code, 1) << far.out;
  EXPECT_NE(far.out.find("far.txt:3"), std::string::npos) << far.out;
  EXPECT_NE(far.out.find("3485 vertices"), std::string::npos) << far.out;
  EXPECT_EQ(iarap_cli("bench '" + (dir / "garbage.off").string() + "'").code, 1);
  EXPECT_FALSE(fs::exists(dir / "o.off"));
  fs::remove_all(dir);
}

// A tetrahedron plus one vertex no face uses: --repair drops it and maps the constraint indices.
TEST(Cli, RepairMapsConstraintIndices) {
  const auto dir = iarap::test::temp_dir("cli_repair");
  write_file(dir / "tet.off", "OFF\n5 4 0\n0 0 0\n9 9 9\n1 0 0\n0 1 0\n0 0 1\n"
                              "3 0 3 2\n3 0 2 4\n3 0 4 3\n3 2 3 4\n");
  write_file(dir / "c.txt", "0 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1.5\n");
  write_file(dir / "removed.txt", "1 9 9 9\n0 0 0 0\n");
  const std::string mesh = " '" + (dir / "tet.off").string() + "'";
  const std::string out = " --out '" + (dir / "o.off").string() + "'";
  // Without repair the stray vertex is kept where it is (it has no energy) and written back unchanged.
  ASSERT_EQ(iarap_cli("deform" + mesh + " --constraints '" + (dir / "c.txt").string() + "'" + out).code, 0);
  const auto kept = iarap::read_mesh((dir / "o.off").string());
  ASSERT_EQ(kept.V.rows(), 5);
  EXPECT_EQ(kept.V.row(1), Eigen::RowVector3d(9, 9, 9));
  const CliRun run =
      iarap_cli("deform" + mesh + " --repair --method spokes-rims --json --quiet --constraints '" +
                (dir / "c.txt").string() + "'" + out);
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_FALSE(parse_json(run)["repair"].empty());
  const auto result = iarap::read_mesh((dir / "o.off").string());
  ASSERT_EQ(result.V.rows(), 4);
  EXPECT_EQ(result.V.row(3), Eigen::RowVector3d(0, 0, 1.5)); // old vertex 4 is new vertex 3
  const CliRun removed = iarap_cli(
      "deform" + mesh + " --repair --constraints '" + (dir / "removed.txt").string() + "'" + out, true);
  EXPECT_EQ(removed.code, 1);
  EXPECT_NE(removed.out.find("constrained vertex 1 was removed"), std::string::npos) << removed.out;
  fs::remove_all(dir);
}

// Two closed tetrahedra touching at vertex 0 (a non-manifold vertex), one face of the second reversed:
// deformed as it is, with its 7 vertices (the tufted cover, issue 47; it was refused before); --repair splits
// vertex 0 (its copy, new vertex 7, keeps the second tetrahedron's faces), orients the face back and
// constrains the copy to vertex 0's target, with every method (issue 33).
TEST(Cli, RepairSplitsAVertexAndConstrainsItsCopies) {
  const auto dir = iarap::test::temp_dir("cli_repair_split");
  write_file(dir / "pinched.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n"
                                  "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"
                                  "f 1 6 5\nf 1 7 5\nf 1 6 7\nf 5 7 6\n");
  write_file(dir / "c.txt", "0 0 0 0.5\n1 1 0 0\n4 -1 0 0\n");
  const std::string args = "deform '" + (dir / "pinched.obj").string() + "' --constraints '" +
                           (dir / "c.txt").string() + "' --out '" + (dir / "o.obj").string() + "' --quiet";
  const CliRun as_it_is = iarap_cli(args, true);
  EXPECT_EQ(as_it_is.code, 0) << as_it_is.out;
  EXPECT_EQ(iarap::read_mesh((dir / "o.obj").string()).V.rows(), 7);
  for (const std::string method : {"arap", "spokes-rims", "iarap"}) {
    const CliRun run = iarap_cli(args + " --repair --json --method " + method);
    ASSERT_EQ(run.code, 0) << run.out;
    const std::string actions = parse_json(run)["repair"].dump();
    EXPECT_NE(actions.find("split 1 non-manifold vertex into one copy per fan of faces (1 copy added)"),
              std::string::npos)
        << actions;
    EXPECT_NE(actions.find("reversed 1 face"), std::string::npos) << actions;
    const auto result = iarap::read_mesh((dir / "o.obj").string());
    ASSERT_EQ(result.V.rows(), 8) << method;
    EXPECT_EQ(result.V.row(0), Eigen::RowVector3d(0, 0, 0.5)) << method;
    EXPECT_EQ(result.V.row(7), Eigen::RowVector3d(0, 0, 0.5)) << method; // the copy, at the same target
    EXPECT_EQ(result.F.row(4), Eigen::RowVector3i(7, 4, 5)) << method;   // (0, 5, 4) reversed, on the copy
  }
  fs::remove_all(dir);
}

TEST(Cli, BenchJsonHasEveryTiming) {
  const CliRun run =
      iarap_cli("bench '" + bunny + "' --methods arap,iarap --iterations 2 --threads 1 --json");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  EXPECT_FALSE(j["cpu"].get<std::string>().empty());
  EXPECT_EQ(j["threads"], 1);
  ASSERT_EQ(j["results"].size(), 2u);
  for (const auto& r : j["results"]) {
    EXPECT_EQ(r["vertices"], 3485);
    EXPECT_EQ(r["threads"], 1);
    EXPECT_EQ(r["measured_iterations"], 2);
    for (const char* key : {"precompute_ms", "intrinsic_ms", "assembly_ms", "factor_ms", "iteration_ms",
                            "local_ms", "global_ms"}) {
      EXPECT_GE(r[key].get<double>(), 0.0) << key;
    }
    EXPECT_GT(r["iteration_ms"].get<double>(), 0.0);
  }
  EXPECT_EQ(j["results"][0]["method"], "arap");
  EXPECT_EQ(j["results"][1]["method"], "iarap");
  EXPECT_GT(j["results"][1]["intrinsic_ms"].get<double>(), 0.0);
}

// The tool's malloc settings (app/malloc_settings.cpp): set by its re-execution unless the user chose, and
// reported by bench so that a benchmark's figures say what they ran under.
TEST(Cli, BenchReportsTheMallocSettings) {
  std::ifstream thp_file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string thp;
  std::getline(thp_file, thp);
  const bool thp_on = !thp.empty() && thp.find("[never]") == std::string::npos;
  const std::string args = "bench '" + bunny + "' --methods arap --iterations 1 --threads 1 --json";
  auto tunables = [&](const std::string& env) {
    const CliRun run = iarap_cli_env(env, args);
    EXPECT_EQ(run.code, 0) << run.out;
    return parse_json(run)["glibc_tunables"].get<std::string>();
  };
  const std::string ours = tunables("-u GLIBC_TUNABLES");
  if (thp_on) {
    EXPECT_EQ(ours,
              "glibc.malloc.hugetlb=1:glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=67108864:"
              "glibc.malloc.trim_threshold=134217728");
  } else {
    EXPECT_EQ(ours, ""); // no re-execution: huge pages would change nothing
  }
  // A setting of the user's is kept and not repeated; the others are added.
  const std::string mixed = tunables("GLIBC_TUNABLES=glibc.malloc.trim_threshold=1048576");
  if (thp_on) {
    EXPECT_EQ(mixed, "glibc.malloc.trim_threshold=1048576:glibc.malloc.hugetlb=1:"
                     "glibc.malloc.mmap_threshold=33554432:glibc.malloc.top_pad=67108864");
  } else {
    EXPECT_EQ(mixed, "glibc.malloc.trim_threshold=1048576");
  }
  // Choosing huge pages (here: off) opts out of every setting of the tool's.
  EXPECT_EQ(tunables("GLIBC_TUNABLES=glibc.malloc.hugetlb=0"), "glibc.malloc.hugetlb=0");
}

TEST(Cli, BenchRoundsKeepEveryRoundAndThePairedMedian) {
  const CliRun run =
      iarap_cli("bench '" + bunny + "' --methods arap,iarap --iterations 1 --rounds 3 --threads 1 --json");
  ASSERT_EQ(run.code, 0) << run.out;
  const json j = parse_json(run);
  for (const auto& r : j["results"]) {
    ASSERT_EQ(r["precompute_ms_rounds"].size(), 3u);
    ASSERT_EQ(r["iteration_ms_rounds"].size(), 3u);
    double fastest = r["precompute_ms_rounds"][0].get<double>();
    for (const auto& ms : r["precompute_ms_rounds"]) fastest = std::min(fastest, ms.get<double>());
    EXPECT_EQ(r["precompute_ms"].get<double>(), fastest); // the table keeps the fastest round
  }
  const CliRun text =
      iarap_cli("bench '" + bunny + "' --methods arap,iarap --iterations 1 --rounds 3 --threads 1");
  ASSERT_EQ(text.code, 0) << text.out;
  EXPECT_NE(text.out.find("iarap / arap: precompute"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("median of 3 paired rounds: precompute"), std::string::npos) << text.out;
}

TEST(Cli, BenchSubdivideAndTable) {
  const CliRun run = iarap_cli("bench '" + bunny + "' --methods spokes-rims --iterations 1 --subdivide 1");
  ASSERT_EQ(run.code, 0) << run.out;
  // One midpoint per edge of a closed mesh: 3485 + 6966 * 3 / 2 vertices.
  EXPECT_NE(run.out.find(" 13934 "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("spokes-rims"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("cpu: "), std::string::npos) << run.out;
}

// bench --converge: every run either reaches the gap (its last energy within TOL of the reference, the lowest
// energy of the reference runs, so never below it by more than rounding), stops at another stationary point
// (the gradient rule of the reference runs), or hits the iteration limit; the table marks which.
TEST(Cli, BenchConvergeReportsReachedOrStationaryRuns) {
  const double tolerance = 1e-3; // a loose gap: the test measures the bench's bookkeeping, not the solvers
  const auto dir = iarap::test::temp_dir("cli_bench_converge");
  const auto report = dir / "converge.json";
  const CliRun run = iarap_cli("bench '" + bunny +
                               "' --converge 1e-3 --methods spokes-rims --accels none,lbfgs "
                               "--max-iterations 2000 --threads 1 --report '" +
                               report.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("within 1e-03 (relative) of the reference minimum"), std::string::npos) << run.out;
  std::ifstream in(report);
  const json j = json::parse(in);
  fs::remove_all(dir);
  ASSERT_EQ(j["results"].size(), 1u);
  const json& r = j["results"][0];
  const double reference = r["reference_energy"].get<double>();
  ASSERT_TRUE(std::isfinite(reference));
  ASSERT_EQ(r["reference_runs"].size(), 3u);
  for (const auto& ref : r["reference_runs"]) // the reference is the lowest of them
    EXPECT_GE(ref["energy"].get<double>(), reference) << ref;
  ASSERT_EQ(r["runs"].size(), 2u);
  for (const auto& x : r["runs"]) {
    const double gap = x["final_energy"].get<double>() - reference;
    EXPECT_DOUBLE_EQ(x["final_gap"].get<double>(), gap) << x;
    EXPECT_LT(x["iterations"].get<int>(), 2000) << x; // spokes-rims on the bunny converges well before
    if (x["reached"].get<bool>()) {
      EXPECT_FALSE(x["stationary"].get<bool>()) << x;
      EXPECT_LE(gap, tolerance * std::abs(reference)) << x;
      EXPECT_GE(gap, -1e-12 * std::abs(reference)) << x; // not below the lowest minimum found
    } else {
      EXPECT_TRUE(x["stationary"].get<bool>()) << x;
      EXPECT_GT(gap, tolerance * std::abs(reference)) << x;
    }
    EXPECT_GE(x["solves"].get<int>(), x["iterations"].get<int>()) << x; // at least one solve an iteration
    EXPECT_GT(x["cpu_ms"].get<double>(), 0.0) << x;                     // the process's CPU time over the run
    EXPECT_EQ(x["newton_from_ms"].get<double>(), 0.0) << x;             // only the hybrid switches
  }
}

// The hybrid's switch in bench --converge: the wall time at the end of its last L-BFGS iteration, within the
// run's (bunny, spokes-rims: the switch comes at iteration 47 of 55 to the 1e-6 gap).
TEST(Cli, BenchConvergeTimesTheHybridsSwitch) {
  const auto dir = iarap::test::temp_dir("cli_bench_converge_hybrid");
  const auto report = dir / "converge.json";
  const CliRun run = iarap_cli(
      "bench '" + bunny + "' --converge 1e-6 --methods spokes-rims --accels hybrid --threads 1 --report '" +
      report.string() + "'");
  ASSERT_EQ(run.code, 0) << run.out;
  std::ifstream in(report);
  const json j = json::parse(in);
  fs::remove_all(dir);
  const json& x = j["results"][0]["runs"][0];
  ASSERT_GT(x["newton_from"].get<int>(), 1) << x;
  EXPECT_GT(x["newton_from_ms"].get<double>(), 0.0) << x;
  EXPECT_LT(x["newton_from_ms"].get<double>(), x["ms"].get<double>()) << x; // Newton's iterations follow
}

// A bunny with one zero-area face: original ARAP refuses it (infinite cotangents), iARAP mollifies it.
// bench reports the failure, still times iARAP, and exits 1.
TEST(Cli, BenchReportsAFailingMethodAndGoesOn) {
  const auto dir = iarap::test::temp_dir("cli_bench_fail");
  auto mesh = iarap::read_mesh(bunny);
  const Eigen::Vector3i face = mesh.F.row(100);
  mesh.V.row(face(2)) = 0.5 * (mesh.V.row(face(0)) + mesh.V.row(face(1)));
  const fs::path flat = dir / "flat_face.off";
  iarap::write_mesh(flat.string(), mesh.V, mesh.F);
  const CliRun run =
      iarap_cli("bench '" + flat.string() + "' --methods arap,iarap --iterations 1 --threads 1 --json");
  EXPECT_EQ(run.code, 1);
  const json j = parse_json(run);
  ASSERT_EQ(j["results"].size(), 2u) << run.out;
  EXPECT_TRUE(j["results"][0].contains("error")) << run.out;
  EXPECT_FALSE(j["results"][1].contains("error")) << run.out;
  EXPECT_GT(j["results"][1]["iteration_ms"].get<double>(), 0.0);
  fs::remove_all(dir);
}

} // namespace
