// A flat mesh through the server's session solves in the plane z = 0 (ArapOptions::planar), as `iarap
// deform` does on the same input: same positions to 1e-12 of the bounding-box diagonal.
//
// The deformation folds a strip (its handle pushed past the fixed end, turned by 150 degrees), so that cells
// pass through a reflection: there the 3D solver fits a rotation that turns the cell over (a reflection in
// the plane) where the planar one keeps a rotation about z, and the two results differ by far more than the
// tolerance (checked below), so the comparison tells the modes apart.
#include "../../app/serve/session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "app/cli_runner.h"
#include "serve_test_meshes.h"
#include "test_support.h"

#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <fstream>

namespace {

using iarap::serve::Session;
using iarap::serve::SolveProgress;
using iarap::serve::SolveRequest;
using iarap::test::grid_column;
using iarap::test::grid_mesh;

constexpr int planar_columns = 12, planar_rows = 3;
constexpr double planar_width = 3.0;

std::string exact(double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 17);
  return std::string(buffer, end);
}

// The handle column's targets: rotated by 150 degrees about the strip's middle (1.5, 0.5), in the plane.
Eigen::MatrixXd folded_targets(const Eigen::MatrixXd& V, const Eigen::VectorXi& handle) {
  const double angle = 150.0 * M_PI / 180.0;
  Eigen::MatrixXd targets(handle.size(), 3);
  for (Eigen::Index k = 0; k < handle.size(); ++k) {
    const double x = V(handle[k], 0) - 1.5, y = V(handle[k], 1) - 0.5;
    targets.row(k) << 1.5 + std::cos(angle) * x - std::sin(angle) * y,
        0.5 + std::sin(angle) * x + std::cos(angle) * y, 0.0;
  }
  return targets;
}

// The solve options both runs use, `iarap deform`'s defaults spelled out.
iarap::ArapSolveOptions solve_options() {
  iarap::ArapSolveOptions options;
  options.max_iterations = 50;
  options.tolerance = 1e-6;
  options.accelerator = iarap::ArapAccelerator::Newton;
  options.window = 8;
  return options;
}

} // namespace

TEST(ServePlanarSession, FlatMeshMatchesDeformInThePlane) {
  const iarap::MeshData mesh = grid_mesh(planar_columns, planar_rows, planar_width);
  const Eigen::VectorXi fixed = grid_column(planar_columns, planar_rows, 0);
  const Eigen::VectorXi handle = grid_column(planar_columns, planar_rows, planar_columns);
  const Eigen::MatrixXd targets = folded_targets(mesh.V, handle);

  // Through the server's session, as POST /api/constraints then POST /api/solve with handle_targets.
  Session session;
  session.load_mesh("strip.off", mesh);
  session.set_constraints(fixed, handle);
  SolveRequest request;
  request.solve = solve_options();
  request.handle_targets = targets;
  SolveProgress progress;
  const iarap::serve::SolveResult result = session.solve(request, progress);
  EXPECT_TRUE(result.planar);
  const Eigen::MatrixXd U = session.snapshot(request.method).V;
  EXPECT_EQ(U.col(2).cwiseAbs().maxCoeff(), 0.0); // in the plane exactly: planar positions have z = 0

  // `iarap deform` on the same mesh and constraints (the OBJ it writes holds every double exactly).
  const std::filesystem::path dir = iarap::test::temp_dir("serve_planar");
  iarap::write_mesh((dir / "strip.off").string(), mesh.V, mesh.F);
  {
    std::ofstream constraints(dir / "strip_constraints.txt");
    for (Eigen::Index k = 0; k < fixed.size(); ++k)
      constraints << fixed[k] << " " << exact(mesh.V(fixed[k], 0)) << " " << exact(mesh.V(fixed[k], 1))
                  << " 0\n";
    for (Eigen::Index k = 0; k < handle.size(); ++k)
      constraints << handle[k] << " " << exact(targets(k, 0)) << " " << exact(targets(k, 1)) << " 0\n";
  }
  const iarap::test::cli::CliRun run = iarap::test::cli::iarap_cli(
      "deform '" + (dir / "strip.off").string() + "' --constraints '" +
      (dir / "strip_constraints.txt").string() + "' --out '" + (dir / "deformed.obj").string() +
      "' --iterations 50 --tolerance 1e-6 --accel newton --window 8 --pin-unconstrained --quiet --json");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json report = iarap::test::cli::parse_json(run);
  const Eigen::MatrixXd deformed = iarap::read_mesh((dir / "deformed.obj").string()).V;
  ASSERT_EQ(deformed.rows(), U.rows());

  const double diagonal = session.mesh_summary().bbox_diagonal;
  const double gap = (U - deformed).cwiseAbs().maxCoeff() / diagonal;
  std::cout << "flat strip (" << U.rows()
            << " vertices, fold by 150 degrees): server vs iarap deform, max |dU| = " << gap
            << " of the bbox diagonal; iterations " << result.report.iterations << " / "
            << report.value("iterations", -1) << "\n";
  EXPECT_LE(gap, 1e-12);
  EXPECT_EQ(result.report.iterations, report.value("iterations", -1));
  EXPECT_TRUE(report.value("planar", false));

  // The same solve in 3D (no planar mode) ends elsewhere: the comparison above can fail.
  iarap::ArapOptions options;
  options.pin_unconstrained_components = true;
  Eigen::VectorXi constrained(fixed.size() + handle.size());
  constrained << fixed, handle;
  Eigen::MatrixXd all_targets(constrained.size(), 3);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) all_targets.row(k) = mesh.V.row(fixed[k]);
  all_targets.bottomRows(handle.size()) = targets;
  iarap::ArapData data = iarap::arap_precompute(mesh.V, mesh.F, constrained, options);
  Eigen::MatrixXd U3 = mesh.V;
  iarap::arap_solve(data, all_targets, U3, solve_options());
  const double gap_3d = (U3 - deformed).cwiseAbs().maxCoeff() / diagonal;
  std::cout << "the 3D solver's result is " << gap_3d << " of the diagonal away\n";
  EXPECT_GT(gap_3d, 1e-6);
  std::filesystem::remove_all(dir);
}
