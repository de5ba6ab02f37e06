// `iarap register` end to end: a fit written with the source's numbering and a JSON report; bad input
// fails naming the file and line, and writes nothing.
#include "app/cli_runner.h"
#include "registration_fixtures.h"

#include "iarap/io/read_mesh.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iomanip>

namespace iarap {
namespace {

namespace fs = std::filesystem;
using test::cli::iarap_cli;

void write_xyz(const fs::path& path, const Eigen::MatrixXd& P) {
  std::ofstream out(path);
  out << std::setprecision(17);
  for (Eigen::Index i = 0; i < P.rows(); ++i) out << P(i, 0) << " " << P(i, 1) << " " << P(i, 2) << "\n";
}

TEST(RegisterCli, FitsAPointCloudAndWritesTheMeshAndReport) {
  const test::KnownDeformation known = test::bunny_deformation();
  const fs::path dir = test::temp_dir("register_cli");
  write_xyz(dir / "scan.xyz", sample_surface(known.U, known.mesh.F, 6000, 46, 0.001 * known.diagonal));
  {
    std::ofstream landmarks(dir / "landmarks.txt");
    landmarks << std::setprecision(17);
    for (int v : {0, 500, 1000, 1500, 2000, 2500, 3000})
      landmarks << v << " " << known.U(v, 0) << " " << known.U(v, 1) << " " << known.U(v, 2) << "\n";
    const Eigen::RowVector3d b(0.2, 0.3, 0.5); // and a point on face 10
    const Eigen::RowVector3d on_face = b(0) * known.U.row(known.mesh.F(10, 0)) +
                                       b(1) * known.U.row(known.mesh.F(10, 1)) +
                                       b(2) * known.U.row(known.mesh.F(10, 2));
    landmarks << "b 10 0.2 0.3 0.5 " << on_face(0) << " " << on_face(1) << " " << on_face(2) << "\n";
  }
  const fs::path out = dir / "fit.off", report = dir / "fit.json";
  const auto run =
      iarap_cli("register '" + test::data_path("bunny.off") + "' '" + (dir / "scan.xyz").string() +
                "' --landmarks '" + (dir / "landmarks.txt").string() + "' --out '" + out.string() +
                "' --report '" + report.string() + "' --stages 3 --rounds 4 --json --quiet");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = test::cli::parse_json(run);
  EXPECT_EQ(j["landmarks"], 8);
  EXPECT_EQ(j["target_normals"], "estimated (PCA)");
  EXPECT_LT(j["final_distance"]["mean"].get<double>(), j["initial_distance"]["mean"].get<double>());
  EXPECT_FALSE(j["rounds"].empty());
  EXPECT_EQ(nlohmann::json::parse(test::cli::read_file(report)), j);
  const MeshData fit = read_mesh(out.string());
  EXPECT_EQ(fit.V.rows(), known.mesh.V.rows());
  EXPECT_EQ(fit.F, known.mesh.F);
}

TEST(RegisterCli, BadInputNamesTheFileAndLineAndWritesNothing) {
  const fs::path dir = test::temp_dir("register_cli_bad");
  test::cli::write_file(dir / "bad.xyz", "0 0 0\n1 0 0\ninf 1 0\n");
  const fs::path out = dir / "fit.off";
  auto run = iarap_cli("register '" + test::data_path("bunny.off") + "' '" + (dir / "bad.xyz").string() +
                           "' --out '" + out.string() + "'",
                       true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find((dir / "bad.xyz").string() + ":3: non-finite x coordinate"), std::string::npos)
      << run.out;
  EXPECT_FALSE(fs::exists(out));

  test::cli::write_file(dir / "scan.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n");
  test::cli::write_file(dir / "landmarks.txt", "# one landmark\n5000 0 0 0\n");
  run = iarap_cli("register '" + test::data_path("bunny.off") + "' '" + (dir / "scan.xyz").string() +
                      "' --landmarks '" + (dir / "landmarks.txt").string() + "' --out '" + out.string() + "'",
                  true);
  EXPECT_EQ(run.code, 1);
  EXPECT_NE(run.out.find((dir / "landmarks.txt").string() + ":2:"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(out));
}

} // namespace
} // namespace iarap
