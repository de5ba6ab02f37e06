// End-to-end tests of `iarap simulate` and `iarap deform --gravity / --forces` (issue 32, items 3-4):
// the damped fall settles to the statics, frames stay at rest without forces, and bad input is refused
// naming the file and line with nothing left in the frame folder.
#include "app/cli_runner.h"
#include "dynamics/dynamics_fixtures.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;

struct Scene {
  fs::path dir, mesh, scenario;
  iarap::test::HeldPatch patch;
};

// The bumpy patch (spanning [0, 1] in x and y) held at its bottom 10% along y.
Scene scene(const std::string& tag) {
  Scene s;
  s.dir = iarap::test::temp_dir("simulate_" + tag);
  s.patch = iarap::test::held_patch(10);
  s.mesh = s.dir / "patch.obj";
  iarap::write_mesh(s.mesh.string(), s.patch.mesh.V, s.patch.mesh.F);
  s.scenario = s.dir / "held.json";
  write_file(s.scenario, R"({"fixed": {"bottom": 0.1, "axis": "y"}})");
  return s;
}

std::string simulate(const Scene& s, const std::string& out, const std::string& extra) {
  return "simulate '" + s.mesh.string() + "' --scenario '" + s.scenario.string() + "' --out-dir '" + out +
         "' --quiet " + extra;
}

double max_distance(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).rowwise().norm().maxCoeff();
}

// Nothing but what was there before: no frame, no report, no staging folder.
bool empty_folder(const fs::path& dir) {
  return !fs::exists(dir) || fs::is_empty(dir);
}

TEST(SimulateCli, DampedFallSettlesToTheGravityStatics) {
  const Scene s = scene("settle");
  const fs::path out = s.dir / "frames", statics = s.dir / "statics.obj";
  const CliRun run = iarap_cli(
      simulate(s, out.string(), "--gravity 0 0 -1 --dt 0.1 --steps 300 --damping 0.2 --every 100 --json"));
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  ASSERT_EQ(j["frames"].size(), 4u); // 0, 100, 200, 300
  ASSERT_EQ(j["per_step"].size(), 300u);
  EXPECT_TRUE(fs::exists(out / "simulation.json"));
  EXPECT_TRUE(fs::exists(out / "frame_000300.obj"));
  const CliRun deform = iarap_cli(
      "deform '" + s.mesh.string() + "' --scenario '" + s.scenario.string() + "' --out '" + statics.string() +
      "' --gravity 0 0 -1 --iterations 2000 --tolerance 0 --grad-tol 1e-10 --quiet "
      "--json");
  ASSERT_EQ(deform.code, 0) << deform.out;
  const nlohmann::json d = parse_json(deform);
  EXPECT_LT(d["potential"].get<double>(), 0.0);
  const Eigen::MatrixXd last = iarap::read_mesh((out / "frame_000300.obj").string()).V;
  const Eigen::MatrixXd equilibrium = iarap::read_mesh(statics.string()).V;
  const double sag = max_distance(equilibrium, s.patch.mesh.V);
  EXPECT_GT(sag, 0.05 * s.patch.diagonal); // gravity 1 visibly sags the unit patch at density 1
  // 300 steps of damping 0.2 shrink the motion by 0.8^300 ~ 1e-29: what is left is the per-step
  // solver tolerance, far below 1% of the sag.
  EXPECT_LT(max_distance(last, equilibrium), 0.01 * sag);
  EXPECT_LT(max_distance(last, equilibrium), 1e-3 * s.patch.diagonal);
  // The kinetic energy dies out; every step reports the three energies.
  const nlohmann::json& first = j["per_step"][0];
  const nlohmann::json& final_step = j["per_step"][299];
  EXPECT_GT(first["kinetic_energy"].get<double>(), 0.0);
  EXPECT_LT(final_step["kinetic_energy"].get<double>(), 1e-8 * first["kinetic_energy"].get<double>());
  EXPECT_GT(final_step["elastic_energy"].get<double>(), 0.0);
  EXPECT_LT(final_step["potential_energy"].get<double>(), 0.0);
}

TEST(SimulateCli, WithoutForcesEveryFrameIsAtRest) {
  const Scene s = scene("rest");
  const fs::path out = s.dir / "frames";
  const CliRun run = iarap_cli(simulate(s, out.string(), "--dt 0.05 --steps 10 --format ply"));
  ASSERT_EQ(run.code, 0) << run.out;
  for (int n = 0; n <= 10; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.ply", n);
    const Eigen::MatrixXd X = iarap::read_mesh((out / name).string()).V;
    EXPECT_LE(max_distance(X, s.patch.mesh.V), 1e-10 * s.patch.diagonal) << name;
  }
}

TEST(SimulateCli, BadNumbersAreUsageErrors) {
  const Scene s = scene("numbers");
  const fs::path out = s.dir / "frames";
  for (const std::string bad :
       {"--dt nan --steps 3", "--dt 0 --steps 3", "--dt -1 --steps 3", "--dt 0.1 --steps 0",
        "--dt 0.1 --steps 3 --gravity 0 nan 0", "--dt 0.1 --steps 3 --gravity 0 1",
        "--dt 0.1 --steps 3 --damping 1", "--dt 0.1 --steps 3 --density 0", "--dt inf --steps 3"}) {
    const CliRun run = iarap_cli(simulate(s, out.string(), bad), true);
    EXPECT_EQ(run.code, 2) << bad << "\n" << run.out;
    EXPECT_TRUE(empty_folder(out)) << bad;
  }
}

// A time step whose inertia weights m / (2 dt^2) overflow or underflow is refused by the library, naming
// dt and the range, not "soft vertex [0] has weight inf" (issue 43); nothing is written.
TEST(SimulateCli, TimeStepsOutOfRangeNameDt) {
  const Scene s = scene("dt_range");
  const fs::path out = s.dir / "frames";
  for (const std::string dt : {"1e-300", "1e+300"}) {
    const CliRun run = iarap_cli(simulate(s, out.string(), "--dt " + dt + " --steps 2"), true);
    EXPECT_EQ(run.code, 1) << run.out;
    EXPECT_NE(run.out.find("dt = " + dt + " is too"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("dt must be in ["), std::string::npos) << run.out;
    EXPECT_EQ(run.out.find("soft vertex"), std::string::npos) << run.out;
    EXPECT_TRUE(empty_folder(out)) << dt;
  }
}

TEST(SimulateCli, BadForcesFilesNameTheLine) {
  const Scene s = scene("forces");
  const fs::path out = s.dir / "frames", forces = s.dir / "forces.txt";
  const std::string n = std::to_string(s.patch.mesh.V.rows());
  for (const auto& [text, expected] : std::vector<std::pair<std::string, std::string>>{
           {"# comment\n3 0 0 -1\n" + n + " 0 0 1\n", "forces.txt:3: vertex index " + n + " out of range"},
           {"3 0 0\n", "forces.txt:1: expected 'index fx fy fz', found 3 token(s)"},
           {"3 0 0 -1 7\n", "forces.txt:1: expected 'index fx fy fz', found 5 token(s)"},
           {"\n3 0 nan 1\n", "forces.txt:2: non-finite fy"},
           {"x 0 0 1\n", "forces.txt:1: bad vertex index 'x'"},
           {"# nothing\n", "forces.txt: no forces"}}) {
    write_file(forces, text);
    const CliRun run =
        iarap_cli(simulate(s, out.string(), "--dt 0.1 --steps 3 --forces '" + forces.string() + "'"), true);
    EXPECT_EQ(run.code, 1) << text;
    EXPECT_NE(run.out.find(expected), std::string::npos) << run.out;
    EXPECT_TRUE(empty_folder(out)) << text;
    const CliRun statics =
        iarap_cli("deform '" + s.mesh.string() + "' --scenario '" + s.scenario.string() + "' --out '" +
                      (s.dir / "x.obj").string() + "' --forces '" + forces.string() + "'",
                  true);
    EXPECT_EQ(statics.code, 1) << text;
    EXPECT_NE(statics.out.find(expected), std::string::npos) << statics.out;
    EXPECT_FALSE(fs::exists(s.dir / "x.obj"));
  }
}

TEST(SimulateCli, AFailedRunLeavesNoFrame) {
  const Scene s = scene("failed");
  const fs::path out = s.dir / "frames", constraints = s.dir / "far.txt";
  // Frame 0 is written before step 1, whose target 1e200 / 3 away overflows the energy (a SolverError).
  write_file(constraints, "0 0 0 0\n1 1e200 0 0\n");
  const CliRun run = iarap_cli("simulate '" + s.mesh.string() + "' --constraints '" + constraints.string() +
                                   "' --out-dir '" + out.string() + "' --dt 0.1 --steps 3 --quiet",
                               true);
  EXPECT_EQ(run.code, 1) << run.out;
  EXPECT_NE(run.out.find("not finite"), std::string::npos) << run.out;
  ASSERT_TRUE(fs::is_directory(out));
  EXPECT_TRUE(fs::is_empty(out)); // neither frame 0 nor the private folder it was written to
}

TEST(SimulateCli, AnOutDirThatIsAFileIsRefusedAndKept) {
  const Scene s = scene("outfile");
  const fs::path out = s.dir / "taken";
  write_file(out, "keep me");
  const CliRun run = iarap_cli(simulate(s, out.string(), "--dt 0.1 --steps 3"), true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("--out-dir is a file"), std::string::npos) << run.out;
  EXPECT_EQ(read_file(out), "keep me");
}

TEST(SimulateCli, ForcesWithoutAHeldComponentAreRefusedByDeform) {
  const Scene s = scene("free");
  // Two copies of the patch, constraints on the first only: the second falls forever.
  const int n = static_cast<int>(s.patch.mesh.V.rows());
  Eigen::MatrixXd V(2 * n, 3);
  V << s.patch.mesh.V, s.patch.mesh.V.rowwise() + Eigen::RowVector3d(2, 0, 0);
  Eigen::MatrixXi F(2 * s.patch.mesh.F.rows(), 3);
  F << s.patch.mesh.F, s.patch.mesh.F.array() + n;
  const fs::path mesh = s.dir / "two.obj", constraints = s.dir / "c.txt";
  iarap::write_mesh(mesh.string(), V, F);
  write_file(constraints, "0 0 0 0\n1 " + std::to_string(V(1, 0)) + " " + std::to_string(V(1, 1)) + " " +
                              std::to_string(V(1, 2)) + "\n");
  const CliRun run = iarap_cli("deform '" + mesh.string() + "' --constraints '" + constraints.string() +
                                   "' --out '" + (s.dir / "x.obj").string() + "' --gravity 0 -1 0 --quiet",
                               true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find("connected component 1"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("no static equilibrium"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(s.dir / "x.obj"));
}

} // namespace
