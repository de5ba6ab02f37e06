// closest_rotation_2d against a brute-force search over the rotation angle.
#include "iarap/solver/closest_rotation_2d.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace iarap {
namespace {

Eigen::Matrix2d rotation(double angle) {
  Eigen::Matrix2d R;
  R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return R;
}

// The best of 2^20 equally spaced angles, refined by golden-section search on the bracket around it: the
// distance is a smooth function of the angle, so the bracket holds the minimizer once the grid is finer
// than the spacing of the (at most two) local extrema.
double brute_force_angle(const Eigen::Matrix2d& J) {
  const auto distance = [&](double angle) { return (J - rotation(angle)).squaredNorm(); };
  const int samples = 1 << 20;
  const double spacing = 2 * M_PI / samples;
  int best = 0;
  for (int k = 1; k < samples; ++k)
    if (distance(k * spacing) < distance(best * spacing)) best = k;
  double lo = (best - 1) * spacing, hi = (best + 1) * spacing;
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 100; ++it) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    if (distance(a) < distance(b))
      hi = b;
    else
      lo = a;
  }
  return 0.5 * (lo + hi);
}

// The angle of R = closest_rotation_2d(J) must match the brute-force minimizer: a minimum of a smooth
// function is flat, so the search finds the angle to about sqrt(eps) / sqrt(curvature); compare the
// distances (equal to ~eps relative) and the angles to 1e-6.
void expect_matches_brute_force(const Eigen::Matrix2d& J) {
  const Eigen::Matrix2d R = closest_rotation_2d(J);
  EXPECT_NEAR((R.transpose() * R - Eigen::Matrix2d::Identity()).norm(), 0, 1e-15) << J;
  EXPECT_NEAR(R.determinant(), 1, 1e-15) << J;
  const Eigen::Matrix2d B = rotation(brute_force_angle(J));
  EXPECT_LE((J - R).squaredNorm(), (J - B).squaredNorm() + 1e-14 * (1 + J.squaredNorm())) << J;
  EXPECT_NEAR((R - B).norm(), 0, 1e-6) << J;
}

TEST(ClosestRotation2d, MatchesBruteForceOnRandomMatrices) {
  std::mt19937 random(31);
  std::uniform_real_distribution<double> entry(-2, 2);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix2d J;
    J << entry(random), entry(random), entry(random), entry(random);
    expect_matches_brute_force(J);
  }
}

TEST(ClosestRotation2d, ReflectionGetsARotationNotItself) {
  // A flipped triangle: J = rotation(0.7) * diag(2, -0.5) has det < 0. Its polar factor is a reflection;
  // the closest rotation is a proper rotation at distance > 0.
  Eigen::Matrix2d J = rotation(0.7) * Eigen::Vector2d(2, -0.5).asDiagonal();
  ASSERT_LT(J.determinant(), 0);
  expect_matches_brute_force(J);
  EXPECT_GT((J - closest_rotation_2d(J)).norm(), 0.5);
}

TEST(ClosestRotation2d, RankOneMatrix) {
  // A triangle collapsed to a segment: J = u v^T.
  Eigen::Matrix2d J = Eigen::Vector2d(1.5, -0.4) * Eigen::RowVector2d(0.3, 0.9);
  ASSERT_NEAR(J.determinant(), 0, 1e-15);
  expect_matches_brute_force(J);
}

TEST(ClosestRotation2d, RotationsAndScaledRotationsAreTheirOwnAnswer) {
  for (double angle : {0.0, 1.0, -2.5, M_PI}) {
    EXPECT_NEAR((closest_rotation_2d(rotation(angle)) - rotation(angle)).norm(), 0, 1e-15);
    EXPECT_NEAR((closest_rotation_2d(3.0 * rotation(angle)) - rotation(angle)).norm(), 0, 1e-15);
  }
}

TEST(ClosestRotation2d, TiesGiveTheIdentity) {
  // Every rotation is at the same distance from 0 and from diag(1, -1): ||J||^2 + 2 for both.
  EXPECT_EQ(closest_rotation_2d(Eigen::Matrix2d::Zero()), Eigen::Matrix2d::Identity());
  Eigen::Matrix2d reflection = Eigen::Vector2d(1, -1).asDiagonal();
  EXPECT_EQ(closest_rotation_2d(reflection), Eigen::Matrix2d::Identity());
  for (double angle : {0.3, 2.0})
    EXPECT_NEAR((reflection - rotation(angle)).squaredNorm(), reflection.squaredNorm() + 2, 1e-14);
}

TEST(ClosestRotation2d, NaNGivesNaN) {
  Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
  J(0, 1) = std::nan("");
  EXPECT_TRUE(closest_rotation_2d(J).array().isNaN().all());
}

} // namespace
} // namespace iarap
