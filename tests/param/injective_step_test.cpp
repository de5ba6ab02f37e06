// first_degenerate_step against the sign of det J(t) sampled along the line.
#include "iarap/param/injective_step.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace iarap {
namespace {

double det_at(const Eigen::Matrix2d& J0, const Eigen::Matrix2d& J1, double t) {
  return (J0 + t * (J1 - J0)).determinant();
}

TEST(FirstDegenerateStep, MatchesSampledSignChange) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> entry(-2, 2);
  int with_root = 0, without_root = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Matrix2d J0, J1;
    J0 << entry(random), entry(random), entry(random), entry(random);
    J1 << entry(random), entry(random), entry(random), entry(random);
    if (J0.determinant() <= 0.05) continue; // keep clear of det J0 ~ 0, where no sampling is fine enough
    const double t = first_degenerate_step(J0, J1);
    // Sampled over [0, 20]: the first sign change of det J(t) brackets the first root.
    const int samples = 20000;
    double first = INFINITY;
    for (int k = 1; k <= samples; ++k) {
      const double s = 20.0 * k / samples;
      if (det_at(J0, J1, s) <= 0) {
        first = s;
        break;
      }
    }
    if (std::isinf(first)) {
      ++without_root;
      // No sign change up to 20: either no root or one beyond the sampled range.
      EXPECT_TRUE(std::isinf(t) || t > 20 - 1e-3) << J0 << "\n" << J1 << " t " << t;
      continue;
    }
    ++with_root;
    // The root lies in (first - spacing, first]; det is zero there to rounding.
    EXPECT_GT(t, first - 20.0 / samples - 1e-12);
    EXPECT_LE(t, first + 1e-12);
    EXPECT_NEAR(det_at(J0, J1, t), 0, 1e-12 * (1 + t * t) * (1 + (J1 - J0).squaredNorm()));
  }
  EXPECT_GT(with_root, 100);
  EXPECT_GT(without_root, 100);
}

TEST(FirstDegenerateStep, LinearAndConstantDeterminants) {
  // J1 - J0 of rank 1 makes det J(t) linear: J0 = I, J1 = diag(1, -1): det = 1 - 2t, root 0.5.
  EXPECT_DOUBLE_EQ(first_degenerate_step(Eigen::Matrix2d::Identity(), Eigen::Vector2d(1, -1).asDiagonal()),
                   0.5);
  // Growing the map never degenerates it.
  EXPECT_TRUE(
      std::isinf(first_degenerate_step(Eigen::Matrix2d::Identity(), 2 * Eigen::Matrix2d::Identity())));
  // A shear keeps det = 1 for every t.
  Eigen::Matrix2d shear = Eigen::Matrix2d::Identity();
  shear(0, 1) = 5;
  EXPECT_TRUE(std::isinf(first_degenerate_step(Eigen::Matrix2d::Identity(), shear)));
  // Shrinking to -I passes through 0 at t = 0.5 (a double root of det = (1 - 2t)^2).
  EXPECT_NEAR(first_degenerate_step(Eigen::Matrix2d::Identity(), -Eigen::Matrix2d::Identity()), 0.5, 1e-7);
}

TEST(FirstDegenerateStep, FlippedStartDoesNotLimit) {
  const Eigen::Matrix2d flipped = Eigen::Vector2d(1, -1).asDiagonal();
  EXPECT_TRUE(std::isinf(first_degenerate_step(flipped, Eigen::Matrix2d::Identity())));
}

} // namespace
} // namespace iarap
