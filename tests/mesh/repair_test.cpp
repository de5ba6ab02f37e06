#include "iarap/core/errors.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "small_meshes.h"

#include <gtest/gtest.h>

TEST(RepairMesh, WeldsASoupBackIntoOneComponent) {
  const auto octa = iarap::test::octahedron();
  auto soup = iarap::test::as_soup(octa);
  // Jitter one copy well inside the tolerance (1e-12 x diagonal ~ 3.5e-12) to test the tolerance path.
  soup.V(5, 0) += 1e-13;
  const iarap::RepairResult r = iarap::repair_mesh(soup.V, soup.F);
  ASSERT_EQ(r.V.rows(), 6);
  ASSERT_EQ(r.F.rows(), 8);
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  EXPECT_TRUE(report.usable());
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.genus, 0);
  EXPECT_EQ(report.coincident_vertices, 0);
  // Each old corner maps to the welded vertex at its position.
  for (Eigen::Index v = 0; v < soup.V.rows(); ++v) {
    ASSERT_GE(r.old_to_new(v), 0);
    EXPECT_LE((r.V.row(r.old_to_new(v)) - soup.V.row(v)).norm(), 1e-12);
  }
  ASSERT_FALSE(r.actions.empty());
  EXPECT_NE(r.actions[0].find("welded 18 vertices"), std::string::npos) << r.actions[0];
}

TEST(RepairMesh, ToleranceSeparatesNearbyVertices) {
  auto soup = iarap::test::as_soup(iarap::test::octahedron());
  soup.V(5, 0) += 1e-6; // far outside 1e-12 x diagonal: stays its own vertex
  EXPECT_EQ(iarap::repair_mesh(soup.V, soup.F).V.rows(), 7);
  iarap::RepairOptions loose;
  loose.weld_tolerance = 1e-3;
  EXPECT_EQ(iarap::repair_mesh(soup.V, soup.F, loose).V.rows(), 6);
}

TEST(RepairMesh, RemovesUnreferencedAndZeroAreaKeepingOrder) {
  Eigen::MatrixXd V(6, 3);
  V << 0, 0, 0, 9, 9, 9, 1, 0, 0, 0, 1, 0, 2, 0, 0, 1, 1, 0;
  Eigen::MatrixXi F(3, 3);
  F << 0, 2, 3, 2, 5, 3, 0, 2, 4; // the last face is flat
  iarap::RepairOptions options;
  options.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(V, F, options);
  Eigen::VectorXi expected(6);
  expected << 0, -1, 1, 2, -1, 3; // vertex 1 unused, vertex 4 only in the flat face
  EXPECT_EQ(r.old_to_new, expected);
  ASSERT_EQ(r.F.rows(), 2);
  EXPECT_EQ(r.F.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(r.V.row(3), V.row(5));
  EXPECT_EQ(r.actions.size(), 2u);

  const iarap::RepairResult keep = iarap::repair_mesh(V, F); // defaults keep zero-area faces
  EXPECT_EQ(keep.F.rows(), 3);
  EXPECT_EQ(keep.V.rows(), 5);
}

TEST(RepairMesh, WeldingDropsCollapsedFaces) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0; // vertex 3 duplicates vertex 1
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 1, 3, 2;
  const iarap::RepairResult r = iarap::repair_mesh(V, F);
  EXPECT_EQ(r.F.rows(), 1);
  EXPECT_EQ(r.old_to_new(3), 1);
}

TEST(RepairMesh, OutOfRangeIndexThrows) {
  auto m = iarap::test::octahedron();
  m.F(4, 2) = 17;
  try {
    iarap::repair_mesh(m.V, m.F);
    ADD_FAILURE() << "expected InputError";
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 4 uses vertex 17"), std::string::npos) << e.what();
  }
}

// Repair at 1e-300: areas there underflow to 0 unless computed on normalised coordinates, so every face
// was "zero area" and dropped.
TEST(Repair, TinyScaleKeepsEveryFace) {
  const auto m = iarap::test::octahedron();
  iarap::RepairOptions options;
  options.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(m.V * 1e-300, m.F, options);
  EXPECT_EQ(r.F.rows(), m.F.rows());
  EXPECT_TRUE(r.actions.empty());
}
