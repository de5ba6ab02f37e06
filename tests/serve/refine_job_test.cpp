// The refinement's energy rule (refinement_converged): the request's tolerance read as the gap left to the
// minimum, estimated from the last two relative decreases, not as one decrease below it.
#include "../../app/serve/refine_job.h" // the tool's sources: tests/ is on the include path, app/ is not

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

namespace iarap::serve {
namespace {

// Decreases d_k = (1 - r) r^k E_0-relative of an iteration converging at rate r: the gap after iterate k is
// r^(k+1), the next decrease's sum. The rule stops at the first k whose estimate d_k r / (1 - r) is within
// the tolerance, which is then exactly the gap (the series is geometric): never above the tolerance.
int first_stop(double rate, double tolerance, double& gap_left) {
  std::array<double, 2> earlier{0, 0};
  for (int k = 0; k < 100000; ++k) {
    const double decrease = (1 - rate) * std::pow(rate, k);
    if (refinement_converged(earlier, decrease, tolerance)) {
      gap_left = std::pow(rate, k + 1);
      return k;
    }
    earlier = {earlier[1], decrease};
  }
  return -1;
}

TEST(ServeRefinementRule, StopsWhereTheGapOfALinearRateIsWithinTheTolerance) {
  for (const double rate : {0.5, 0.9, 0.99}) {
    double gap = 0;
    const int k = first_stop(rate, 1e-6, gap);
    ASSERT_GE(k, 0) << rate;
    EXPECT_LE(gap, 1e-6 * (1 + 1e-9)) << rate;
    // Not later than needed: one iterate earlier the gap was r^k > 1e-6 (within rounding of pow).
    EXPECT_GT(gap / rate, 1e-6 * (1 - 1e-9)) << rate;
  }
}

TEST(ServeRefinementRule, OneSmallDecreaseIsNotEnough) {
  // 5e-7 after 2e-6: the rate 0.25 leaves 5e-7 * 0.25 / 0.75 = 1.7e-7, within 1e-6: a stop. After 6e-7
  // (rate 0.83) the estimate is 2.5e-6.
  EXPECT_TRUE(refinement_converged({0, 2e-6}, 5e-7, 1e-6));
  EXPECT_FALSE(refinement_converged({0, 6e-7}, 5e-7, 1e-6));
  // Uneven steps (Newton's, cut short by the trust region): 2.8e-6, 2e-6 then 5e-7: the slower rate 0.71 of
  // the two counts, 5e-7 * 0.71 / 0.29 = 1.2e-6 left: go on.
  EXPECT_FALSE(refinement_converged({2.8e-6, 2e-6}, 5e-7, 1e-6));
  EXPECT_FALSE(refinement_converged({0, 0}, 5e-7, 1e-6));    // no previous decrease yet
  EXPECT_FALSE(refinement_converged({0, 4e-7}, 5e-7, 1e-6)); // decreases that grow: no rate to estimate from
  EXPECT_FALSE(refinement_converged({0, 1e-3}, 2e-6, 1e-6)); // above the tolerance
  // Newton's end-game: 1e-2, 1e-4 then 1e-8 (quadratic); and a decrease of zero or below (rounding at the
  // minimum) ends it whatever came before.
  EXPECT_TRUE(refinement_converged({1e-2, 1e-4}, 1e-8, 1e-6));
  EXPECT_TRUE(refinement_converged({0, 0}, 0.0, 1e-6));
  EXPECT_TRUE(refinement_converged({1e-2, 1e-3}, -1e-15, 1e-6));
}

TEST(ServeRefinementRule, DecreasesAtTheRoundingOfTheEnergyEndIt) {
  // Accepted steps at the minimum gain a few ulps at random (the bunny's refinement: -5e-16 to +5e-16), so
  // their rate may read 1 or more; each ends it on its own, after shrinking decreases or not.
  for (const double ulps : {1.0, 3.0, 50.0}) {
    const double decrease = ulps * std::numeric_limits<double>::epsilon();
    EXPECT_TRUE(refinement_converged({1e-9, 2e-9}, decrease, 1e-6)) << ulps;
    EXPECT_TRUE(refinement_converged({decrease, decrease / 2}, decrease, 1e-6)) << ulps;
  }
  // Above that level a decrease still needs its rate: 1e-12 after 1e-12 (no shrinking) goes on.
  EXPECT_FALSE(refinement_converged({1e-12, 1e-12}, 1e-12, 1e-6));
}

} // namespace
} // namespace iarap::serve
