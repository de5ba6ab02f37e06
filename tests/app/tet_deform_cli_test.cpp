// `iarap deform` on tetrahedral meshes (.mesh .node/.ele .msh): volumetric ARAP, .mesh or surface output,
// the volume ratio in the report.
#include "cli_runner.h"
#include "iarap/io/read_tet_mesh.h"
#include "iarap/io/write_tet_mesh.h"
#include "test_support.h"

#include "../solver/tet_fixtures.h"

#include <cmath>
#include <string>

namespace {

using namespace iarap::test::cli;

// A 6 x 1 x 1 bar written as MEDIT, and constraints holding its x = 0 end and moving its x = 6 end up by 1.
struct TetBarFiles {
  std::filesystem::path dir = iarap::test::temp_dir("tet_cli");
  iarap::test::TetBar bar = iarap::test::tet_bar(6, 1, 1);
  std::string mesh = (dir / "bar.mesh").string(), constraints = (dir / "bar.txt").string();
  TetBarFiles() {
    iarap::write_tet_mesh(mesh, bar.V, bar.T);
    std::string text;
    for (Eigen::Index v = 0; v < bar.V.rows(); ++v)
      if (bar.V(v, 0) == 0.0 || bar.V(v, 0) == 6.0)
        text += std::to_string(v) + " " + std::to_string(bar.V(v, 0)) + " " + std::to_string(bar.V(v, 1)) +
                " " + std::to_string(bar.V(v, 2) + (bar.V(v, 0) == 6.0 ? 1.0 : 0.0)) + "\n";
    write_file(constraints, text);
  }
  // `iarap deform` on the bar with its constraints, writing `out` (a file name in dir).
  CliRun deform(const std::string& out, const std::string& flags, bool merge_stderr = false) const {
    return iarap_cli("deform '" + mesh + "' --constraints '" + constraints + "' --out '" +
                         (dir / out).string() + "' " + flags,
                     merge_stderr);
  }
};

TEST(TetDeformCli, MeshInMeshOutKeepsTheTetrahedraAndReportsTheVolumeRatio) {
  const TetBarFiles files;
  const CliRun run = files.deform("out.mesh", "--json --quiet --grad-tol 1e-8");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j["tetrahedra"], files.bar.T.rows());
  EXPECT_EQ(j["faces"], 4 * (6 + 6 + 1)); // the boundary: two triangles per square
  EXPECT_GT(j["volume_ratio"].get<double>(), 0.95);
  EXPECT_LT(j["volume_ratio"].get<double>(), 1.05);
  EXPECT_FALSE(j.contains("intrinsic"));
  const iarap::TetMesh result = iarap::read_tet_mesh((files.dir / "out.mesh").string());
  EXPECT_EQ(result.T, files.bar.T);
  EXPECT_NEAR(result.V(files.bar.vertex(6, 1, 1), 2), 2.0, 1e-12); // a constrained corner at its target
}

TEST(TetDeformCli, SurfaceOutputKeepsTheTetMeshNumberingAndSurfaceMethodsAreRefused) {
  const TetBarFiles files;
  const CliRun run = files.deform("out.off", "--quiet");
  ASSERT_EQ(run.code, 0) << run.out;
  const std::string off = read_file(files.dir / "out.off");
  EXPECT_EQ(off.rfind("OFF\n" + std::to_string(files.bar.V.rows()) + " 52 0\n", 0), 0u) << off.substr(0, 40);
  const CliRun method = files.deform("out.off", "--method arap --quiet", true);
  EXPECT_NE(method.code, 0);
  EXPECT_NE(method.out.find("surface energy"), std::string::npos) << method.out;
  const CliRun repair = files.deform("out.off", "--repair", true);
  EXPECT_NE(repair.code, 0);
  EXPECT_NE(repair.out.find("tetrahedral"), std::string::npos) << repair.out;
}

} // namespace
