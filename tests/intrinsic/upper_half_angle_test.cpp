// The branch-free atan2 of the signpost corner angles against std::atan2.
#include "intrinsic/upper_half_angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace {

using iarap::detail::upper_half_angle;

// Distance in units in the last place of `exact` (its spacing at that magnitude; the spacing at the
// smallest normal for 0).
double ulps(double value, double exact) {
  const double magnitude = std::max(std::fabs(exact), std::numeric_limits<double>::min());
  return std::fabs(value - exact) / (std::nextafter(magnitude, 2 * magnitude) - magnitude);
}

// The polynomial's own error is 8e-18 relative; the reduction, the evaluation and the two reflections add
// a few roundings of values at most pi: 4 ulp of the result (2 seen on ten million random arguments).
constexpr double kUlps = 4.0;

TEST(UpperHalfAngle, MatchesAtan2OnRandomArguments) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-12.0, 12.0);
  double worst = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    const double y = std::fabs(unit(rng)) * std::pow(10.0, exponent(rng));
    double x = unit(rng) * std::pow(10.0, exponent(rng));
    if (i % 5 == 0)
      x = std::copysign(y * 0.41421356237309504880 * (1 + 1e-12 * unit(rng)), x); // at the reduction
    if (i % 7 == 0) x = std::copysign(y * (1 + 1e-12 * unit(rng)), x);            // near pi/4, 3 pi/4
    worst = std::max(worst, ulps(upper_half_angle(y, x), std::atan2(y, x)));
  }
  EXPECT_LE(worst, kUlps);
}

TEST(UpperHalfAngle, TriangleCornersAndNeedles) {
  // A corner of a triangle with sides b, c around it and a opposite: y = 4 area, x = b^2 + c^2 - a^2.
  auto corner = [](double a, double b, double c) {
    const double s = (a + b + c) / 2;
    return upper_half_angle(4 * std::sqrt(s * (s - a) * (s - b) * (s - c)), b * b + c * c - a * a);
  };
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(corner(1, 1, 1), pi / 3, 4e-16);
  EXPECT_NEAR(corner(5, 3, 4), pi / 2, 4e-16); // the right angle of the 3-4-5 triangle
  EXPECT_NEAR(corner(3, 4, 5), std::atan2(3.0, 4.0), 4e-16);
  // A needle's tiny angle keeps its relative accuracy, its obtuse one is pi minus the others.
  const double tiny = upper_half_angle(1e-9, 1.0);
  EXPECT_LE(ulps(tiny, std::atan2(1e-9, 1.0)), kUlps);
  EXPECT_LE(ulps(upper_half_angle(1e-9, -1.0), std::atan2(1e-9, -1.0)), kUlps);
}

TEST(UpperHalfAngle, AxesAndOrigin) {
  const double pi = 3.14159265358979323846;
  EXPECT_EQ(upper_half_angle(0.0, 1.0), 0.0);
  EXPECT_EQ(upper_half_angle(0.0, -1.0), pi);
  EXPECT_EQ(upper_half_angle(1.0, 0.0), pi / 2);
  EXPECT_EQ(upper_half_angle(0.0, 0.0), 0.0);
  EXPECT_TRUE(std::isnan(upper_half_angle(std::nan(""), 1.0)));
  EXPECT_TRUE(std::isnan(upper_half_angle(1.0, std::nan(""))));
}

} // namespace
