// map_distortion on maps whose distortion is known in closed form, and the 2x2 singular values against
// Eigen's SVD.
#include "iarap/param/map_distortion.h"

#include "param/disk_meshes.h"

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include <random>

namespace iarap {
namespace {

TEST(SingularValues2d, MatchJacobiSvd) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> entry(-3, 3);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix2d J;
    J << entry(random), entry(random), entry(random), entry(random);
    const Eigen::Vector2d reference = Eigen::JacobiSVD<Eigen::Matrix2d>(J).singularValues();
    EXPECT_NEAR((singular_values_2d(J) - reference).norm(), 0, 1e-14 * (1 + J.norm())) << J;
  }
}

TEST(MapDistortion, ScaledIsometryOfASquare) {
  // UV = 2 (x, y) of the unit square: J = 2 I everywhere, R = I, ||J - R||^2 = 2, energy = 2 x area; the
  // best scale 1/2 makes it an isometry.
  const test::TestMesh square = test::flat_square(3);
  const TriangleFrames frames = triangle_frames(square.V, square.F);
  const MapDistortion d = map_distortion(frames, square.F, 2 * square.V.leftCols(2));
  EXPECT_NEAR(d.energy, 2.0, 1e-13);
  EXPECT_NEAR(d.best_scale, 0.5, 1e-15);
  EXPECT_NEAR(d.scaled_energy, 0, 1e-26);
  EXPECT_EQ(d.flipped, 0);
  EXPECT_NEAR(d.min_det_J, 4, 1e-13);
  EXPECT_NEAR(d.area_ratio.min, 4, 1e-13);
  EXPECT_NEAR(d.area_ratio.max, 4, 1e-13);
  EXPECT_NEAR(d.angle_ratio.median, 1, 1e-13);
}

TEST(MapDistortion, StretchAndMirror) {
  const test::TestMesh square = test::flat_square(2);
  const TriangleFrames frames = triangle_frames(square.V, square.F);
  // u = 3x, v = y: sigma = (3, 1) everywhere.
  Eigen::MatrixXd UV = square.V.leftCols(2);
  UV.col(0) *= 3;
  MapDistortion d = map_distortion(frames, square.F, UV);
  EXPECT_NEAR(d.angle_ratio.min, 3, 1e-13);
  EXPECT_NEAR(d.angle_ratio.max, 3, 1e-13);
  EXPECT_NEAR(d.area_ratio.median, 3, 1e-13);
  // J = diag(3, 1), R = I: ||J - R||^2 = 4 per unit area.
  EXPECT_NEAR(d.energy, 4, 1e-13);
  // Mirrored: every triangle flipped, det J = -3.
  UV.col(0) *= -1;
  d = map_distortion(frames, square.F, UV);
  EXPECT_EQ(d.flipped, square.F.rows());
  EXPECT_NEAR(d.min_det_J, -3, 1e-13);
}

} // namespace
} // namespace iarap
