#include "iarap/core/errors.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/mesh/validate.h"
#include "small_meshes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace {

Eigen::Vector3d face_normal(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
  return (b - a).cross(c - a);
}

} // namespace

TEST(SubdivideMidpoint, OneToFourKeepsVerticesOrientationAndArea) {
  const auto m = iarap::test::octahedron();
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  iarap::subdivide_midpoint(m.V, m.F, V, F);
  ASSERT_EQ(V.rows(), 6 + 12);
  ASSERT_EQ(F.rows(), 32);
  EXPECT_EQ(V.topRows(6), m.V);
  double area_before = 0, area_after = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d parent = face_normal(m.V, m.F, f);
    area_before += 0.5 * parent.norm();
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d child = face_normal(V, F, 4 * f + c);
      area_after += 0.5 * child.norm();
      // Planar split: each child is the parent scaled by 1/2, so its normal is exactly parent / 4.
      EXPECT_NEAR((child - parent / 4).norm(), 0.0, 1e-15 * parent.norm());
    }
  }
  EXPECT_NEAR(area_after, area_before, 1e-14 * area_before);
  const iarap::MeshReport r = iarap::check_mesh(V, F);
  EXPECT_TRUE(r.usable());
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.coincident_vertices, 0);
}

TEST(SubdivideMidpoint, BadIndexThrowsAndAliasingWorks) {
  auto m = iarap::test::octahedron();
  Eigen::MatrixXd V = m.V;
  Eigen::MatrixXi F = m.F;
  iarap::subdivide_midpoint(V, F, V, F); // in place
  EXPECT_EQ(V.rows(), 18);
  EXPECT_EQ(F.rows(), 32);
  m.F(7, 0) = 6;
  Eigen::MatrixXd V_out;
  Eigen::MatrixXi F_out;
  EXPECT_THROW(iarap::subdivide_midpoint(m.V, m.F, V_out, F_out), iarap::InputError);
}
