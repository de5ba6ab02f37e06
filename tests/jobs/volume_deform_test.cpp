// Volumetric deformation of a closed surface (iarap/jobs/volume_deform.h): TetGen's tetrahedra keep the
// surface exactly, the surface's constraints carry over, and the solid keeps its volume better than the
// surface energy does.
#include "iarap/jobs/volume_deform.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/scene/read_scenario.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <set>
#include <string>

namespace iarap {
namespace {

// deform --volume runs Debian's tetgen program (scripts/install_deps.sh installs it); without it the tests
// that need it are skipped, saying why.
bool tetgen_on_path() {
  const char* path = std::getenv("PATH");
  std::string folders = path ? path : "";
  for (size_t start = 0; start <= folders.size();) {
    const size_t end = std::min(folders.find(':', start), folders.size());
    if (access((folders.substr(start, end - start) + "/tetgen").c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

#define REQUIRE_TETGEN()                                                                                     \
  if (!tetgen_on_path()) GTEST_SKIP() << "the tetgen program is not on PATH (apt-get install tetgen)"

// A face as its rotation starting at its smallest index (orientation kept).
std::array<int, 3> canonical(int a, int b, int c) {
  if (b < a && b < c) return {b, c, a};
  if (c < a && c < b) return {c, a, b};
  return {a, b, c};
}

std::set<std::array<int, 3>> face_set(const Eigen::MatrixXi& F) {
  std::set<std::array<int, 3>> out;
  for (Eigen::Index f = 0; f < F.rows(); ++f) out.insert(canonical(F(f, 0), F(f, 1), F(f, 2)));
  return out;
}

TEST(VolumeDeform, EnclosedVolumeOfACube) {
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixXi F(12, 3); // outward
  F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3,
      4, 7;
  EXPECT_DOUBLE_EQ(enclosed_volume(V, F), 1.0);
  EXPECT_DOUBLE_EQ(enclosed_volume(2.0 * V, F), 8.0);
  EXPECT_DOUBLE_EQ(enclosed_volume(V, F.rowwise().reverse()), -1.0);
}

// The bunny's inside: its vertices first and bit for bit, its faces the boundary (oriented outward), and the
// tetrahedra fill exactly the volume the surface encloses (a sum of the same determinants regrouped:
// rounding, 1e-12 relative).
TEST(VolumeDeform, TetgenKeepsTheSurface) {
  REQUIRE_TETGEN();
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const TetMesh tets = tetrahedralize_inside(bunny.V, bunny.F);
  ASSERT_GT(tets.V.rows(), bunny.V.rows());
  EXPECT_EQ((tets.V.topRows(bunny.V.rows()) - bunny.V).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(face_set(tet_boundary_faces(tets.T)), face_set(bunny.F));
  const double inside = tet_signed_volumes(tets.V, tets.T).sum();
  EXPECT_NEAR(inside, enclosed_volume(bunny.V, bunny.F), 1e-12 * inside);
  EXPECT_GT(tet_signed_volumes(tets.V, tets.T).minCoeff(), 0.0);
}

TEST(VolumeDeform, MissingOrFailingProgramIsAnError) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  TetgenOptions missing;
  missing.program = "no-such-tetgen-program";
  try {
    tetrahedralize_inside(bunny.V, bunny.F, missing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-tetgen-program"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("apt-get install tetgen"), std::string::npos) << e.what();
  }
  TetgenOptions failing;
  failing.program = "/bin/false"; // coreutils: exits with status 1
  try {
    tetrahedralize_inside(bunny.V, bunny.F, failing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exit status 1"), std::string::npos) << e.what();
  }
  TetgenOptions moving; // without -Y TetGen may split the surface's faces
  moving.switches = "pqQa0.000001";
  EXPECT_THROW(tetrahedralize_inside(bunny.V, bunny.F, moving), InputError);
}

TEST(VolumeDeform, SceneCarriesTheSurfacesConstraintsAndRefusesOpenSurfacesAndFacePoints) {
  REQUIRE_TETGEN();
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const DeformConstraints constraints{read_scenario(test::data_path("bend60_scenario.json")), {}};
  DeformScene surface = prepare_deform(bunny, constraints);
  surface.rigid_groups = {{0, 1, 2}};
  surface.stiffness = Eigen::VectorXd::Constant(bunny.V.rows(), 2.0);
  const DeformScene scene = volume_scene(surface);
  EXPECT_EQ(scene.constraints.fixed, surface.constraints.fixed);
  EXPECT_EQ(scene.constraints.targets, surface.constraints.targets);
  EXPECT_EQ(scene.rigid_groups, surface.rigid_groups);
  ASSERT_EQ(scene.stiffness.size(), scene.mesh.V.rows());
  EXPECT_EQ(scene.stiffness.head(bunny.V.rows()).minCoeff(), 2.0);
  EXPECT_EQ(scene.stiffness.tail(scene.mesh.V.rows() - bunny.V.rows()).maxCoeff(), 1.0);
  EXPECT_EQ(scene.tets.rows() > 0, true);

  DeformScene open = surface;
  open.check.boundary_edges = 3; // as check_mesh reports an open surface
  open.check.boundary_loops = 1;
  EXPECT_THROW(volume_scene(open), InputError);
  DeformScene face_points = surface;
  face_points.constraints.soft.faces = Eigen::VectorXi::Constant(1, 0);
  EXPECT_THROW(volume_scene(face_points), InputError);
}

// The scene: bend60 on the bunny. The solid's enclosed volume changes less than the surface's under
// surface iARAP (measured: docs/cli.md), and the surface comes back with its own vertices and faces.
TEST(VolumeDeform, SolidKeepsItsVolumeBetterThanSurfaceIarap) {
  REQUIRE_TETGEN();
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const DeformConstraints constraints{read_scenario(test::data_path("bend60_scenario.json")), {}};
  const DeformScene surface = prepare_deform(bunny, constraints);
  const DeformScene solid = volume_scene(surface);
  ArapSolveOptions newton;
  newton.max_iterations = 30;
  const DeformResult shell = solve_deform(surface, ArapOptions{}, newton);
  const DeformResult body = solve_deform(solid, ArapOptions{}, newton);
  const Eigen::Index n = bunny.V.rows();
  const double before = enclosed_volume(bunny.V, bunny.F);
  const double shell_change = std::abs(enclosed_volume(shell.U, bunny.F) / before - 1.0);
  const double body_change = std::abs(enclosed_volume(body.U.topRows(n), bunny.F) / before - 1.0);
  EXPECT_LT(body_change, shell_change);
  // The constrained vertices are on their targets in both.
  for (Eigen::Index k = 0; k < surface.constraints.fixed.size(); ++k)
    EXPECT_LT((body.U.row(surface.constraints.fixed(k)) - surface.constraints.targets.row(k)).norm(),
              1e-12 * surface.check.bbox_diagonal);
}

} // namespace
} // namespace iarap
