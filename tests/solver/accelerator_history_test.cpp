// Warm starts of L-BFGS and Anderson across arap_solve calls (ArapSolveOptions::accelerator_history), the
// hybrid accelerator (L-BFGS, then Newton once it stalls: hybrid_iteration.h) and the free rows of L kept
// in ArapData between solves (free_row_system.h).
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "solver/hybrid_iteration.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

namespace iarap {
namespace {

class AcceleratorHistory : public test::SingleThreadTest {
protected:
  void SetUp() override {
    test::SingleThreadTest::SetUp();
    mesh_ = test::bumpy_patch(12);
    fixed_ = test::both_ends(mesh_.V, 0, 0.15, low_);
    targets_ = test::rows_of(mesh_.V, fixed_);
    // A large edit (0.6 of the unit patch up), so that the first iterations move far and the tail is long.
    for (Eigen::Index k = low_; k < fixed_.size(); ++k) targets_(k, 2) += 0.6;
    options_.tolerance = -1;
  }
  ArapReport solve(ArapData& data, Eigen::MatrixXd& U, const ArapSolveOptions& options) const {
    return arap_solve(data, targets_, U, options);
  }
  test::SolverMesh mesh_;
  Eigen::VectorXi fixed_;
  Eigen::Index low_ = 0; // fixed_'s first low_ vertices are the end at rest
  Eigen::MatrixXd targets_;
  ArapSolveOptions options_;
};

// Two calls that hand the history on run the iterates of one call: the second recomputes the energy and
// gradient at the same positions and sees the same pairs / differences.
TEST_F(AcceleratorHistory, TwoCallsHandingTheHistoryOnEqualOneCall) {
  for (const ArapAccelerator accelerator : {ArapAccelerator::Lbfgs, ArapAccelerator::Anderson}) {
    SCOPED_TRACE(arap_accelerator_name(accelerator));
    ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
    options_.accelerator = accelerator;
    Eigen::MatrixXd whole = mesh_.V, cut = mesh_.V;
    options_.max_iterations = 10;
    const ArapReport one = solve(data, whole, options_);
    ASSERT_TRUE(one.accelerator_history);

    options_.max_iterations = 5;
    const ArapReport first = solve(data, cut, options_);
    ArapSolveOptions warm = options_;
    warm.accelerator_history = first.accelerator_history;
    const ArapReport second = solve(data, cut, warm);
    EXPECT_EQ(second.accelerator_history, first.accelerator_history); // continued in place, not copied
    // Measured 4e-15 on this unit-size patch; 1e-11 leaves room for other compilers and rounding of the
    // rotation fits, which restart cold in the second call.
    EXPECT_LE((cut - whole).cwiseAbs().maxCoeff(), 1e-11);
    EXPECT_NEAR(second.energies.back(), one.energies.back(), 1e-11 * one.energies.back());
    // The steps were accelerated from the first iteration of the second call on (a cold one starts plain).
    EXPECT_EQ(second.accepted.front(), 1);
  }
}

// A warm second call on unchanged targets converges in fewer iterations than a cold one from the same
// positions, to the same minimum, once the first call is past the early phase: its pairs / differences then
// describe the curvature near the minimum (measured on this patch, to a 1e-9 relative gradient: L-BFGS 52 vs
// 58 and Anderson 62 vs 80 iterations cut after 20; the hybrid, cut after 10 and already in Newton's phase,
// 11 vs 39). Cut after 3-10 iterations, L-BFGS's and Anderson's histories are of the far-away start, and warm
// and cold were within 20% either way (docs/accelerators.md).
TEST_F(AcceleratorHistory, WarmSecondCallTakesFewerIterationsToTheSameMinimum) {
  for (const auto& [accelerator, cut] :
       {std::pair(ArapAccelerator::Lbfgs, 20), std::pair(ArapAccelerator::Anderson, 20),
        std::pair(ArapAccelerator::Hybrid, 10)}) {
    SCOPED_TRACE(arap_accelerator_name(accelerator));
    ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
    options_.accelerator = accelerator;
    options_.max_iterations = cut;
    Eigen::MatrixXd U = mesh_.V;
    const ArapReport first = solve(data, U, options_);
    ArapSolveOptions rest = options_;
    rest.max_iterations = 2000;
    rest.gradient_tolerance = 1e-9; // of the second call's initial gradient: the same for both
    Eigen::MatrixXd U_cold = U, U_warm = U;
    const ArapReport cold = solve(data, U_cold, rest);
    rest.accelerator_history = first.accelerator_history;
    const ArapReport warm = solve(data, U_warm, rest);
    ASSERT_TRUE(cold.converged);
    ASSERT_TRUE(warm.converged);
    EXPECT_LT(warm.iterations, cold.iterations);
    // At a 1e-9 relative gradient both are at the minimum to about (1e-9)^2 of the energy scale.
    EXPECT_NEAR(warm.energies.back(), cold.energies.back(), 1e-9 * cold.energies.back());
  }
}

TEST_F(AcceleratorHistory, HistoryOfAnotherAcceleratorStartsCold) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  options_.max_iterations = 5;
  options_.accelerator = ArapAccelerator::Lbfgs;
  Eigen::MatrixXd U = mesh_.V;
  const ArapReport lbfgs = solve(data, U, options_);
  ArapSolveOptions anderson = options_;
  anderson.accelerator = ArapAccelerator::Anderson;
  Eigen::MatrixXd U_cold = U, U_given = U;
  const ArapReport cold = solve(data, U_cold, anderson);
  anderson.accelerator_history = lbfgs.accelerator_history;
  const ArapReport given = solve(data, U_given, anderson);
  EXPECT_TRUE(U_given == U_cold);
  EXPECT_EQ(given.energies, cold.energies);
  EXPECT_EQ(given.accelerator_history, lbfgs.accelerator_history); // the same object, reset to Anderson's
}

TEST_F(AcceleratorHistory, HistoryOfAnotherProblemIsRefusedByName) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  options_.accelerator = ArapAccelerator::Lbfgs;
  options_.max_iterations = 2;
  Eigen::MatrixXd U = mesh_.V;
  const ArapReport report = solve(data, U, options_);
  const test::SolverMesh other = test::bumpy_patch(8);
  Eigen::Index low = 0;
  const Eigen::VectorXi fixed = test::both_ends(other.V, 0, 0.15, low);
  ArapData other_data = arap_precompute(other.V, other.F, fixed);
  Eigen::MatrixXd U_other = other.V;
  ArapSolveOptions options = options_;
  options.accelerator_history = report.accelerator_history;
  EXPECT_THROW(
      try {
        arap_solve(other_data, test::rows_of(other.V, fixed), U_other, options);
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("accelerator_history"), std::string::npos) << e.what();
        throw;
      },
      InputError);
}

// The hybrid ends where Newton does (to the 1e-9 relative gradient both run to), after switching.
TEST_F(AcceleratorHistory, HybridSwitchesToNewtonAndReachesItsMinimum) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  options_.max_iterations = 500;
  options_.gradient_tolerance = 1e-9;
  options_.accelerator = ArapAccelerator::Newton;
  Eigen::MatrixXd U_newton = mesh_.V, U_hybrid = mesh_.V;
  const ArapReport newton = solve(data, U_newton, options_);
  options_.accelerator = ArapAccelerator::Hybrid;
  const ArapReport hybrid = solve(data, U_hybrid, options_);
  ASSERT_TRUE(newton.converged);
  ASSERT_TRUE(hybrid.converged);
  EXPECT_EQ(hybrid.accelerator, ArapAccelerator::Hybrid);
  EXPECT_GT(hybrid.newton_from_iteration, 1);
  EXPECT_GT(hybrid.newton_trust_radius, 0); // Newton's state, to hand on
  EXPECT_NEAR(hybrid.energies.back(), newton.energies.back(), 1e-9 * newton.energies.back());
  EXPECT_LE((U_hybrid - U_newton).cwiseAbs().maxCoeff(), 1e-6); // the same minimum (unit-size patch)
  // Newton reports no history; a continued hybrid goes on with Newton from its first iteration.
  EXPECT_FALSE(newton.accelerator_history);
  ArapSolveOptions more = options_;
  more.max_iterations = 2;
  more.gradient_tolerance = 0;
  more.accelerator_history = hybrid.accelerator_history;
  const ArapReport continued = solve(data, U_hybrid, more);
  EXPECT_EQ(continued.newton_from_iteration, 1);
}

// The rule on energies E_k = 1 + q^k: the mean relative decrease of the last kSpan iterations,
// (q^(k - span) - q^k) / span / E_k, falls below the threshold first at the k computed here.
TEST(StallRule, HoldsOnceTheMeanRelativeDecreaseFallsBelowTheThreshold) {
  using detail::StallRule;
  const double q = 0.7, threshold = StallRule::kStall;
  const auto E = [q](int k) { return 1.0 + std::pow(q, k); };
  int expected = -1;
  for (int k = StallRule::kSpan; expected < 0; ++k)
    if ((E(k - StallRule::kSpan) - E(k)) / StallRule::kSpan <= threshold * E(k)) expected = k;
  StallRule rule;
  int first = -1;
  for (int k = 0; k <= expected + 2 && first < 0; ++k)
    if (rule.stalled(E(k))) first = k;
  EXPECT_EQ(first, expected);
}

// The free rows of L are kept in ArapData between solves; a new constrained set or new soft weights
// replace them, so that a solve after arap_set_fixed is the solve of data precomputed with that set.
TEST_F(AcceleratorHistory, KeptFreeRowsFollowTheConstrainedSetAndSoftWeights) {
  options_.accelerator = ArapAccelerator::Lbfgs;
  options_.max_iterations = 5;
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  Eigen::MatrixXd U = mesh_.V;
  solve(data, U, options_);
  ASSERT_TRUE(data.free_rows);
  // One end only: fewer constrained vertices, other free rows.
  const Eigen::VectorXi one_end = fixed_.head(low_);
  arap_set_fixed(data, one_end);
  EXPECT_FALSE(data.free_rows);
  ArapData fresh = arap_precompute(mesh_.V, mesh_.F, one_end);
  Eigen::MatrixXd targets = test::rows_of(mesh_.V, one_end);
  targets.col(2).array() += 0.1;
  Eigen::MatrixXd U_kept = mesh_.V, U_fresh = mesh_.V;
  arap_solve(data, targets, U_kept, options_);
  arap_solve(fresh, targets, U_fresh, options_);
  EXPECT_TRUE(U_kept == U_fresh);

  // Soft weights change L + Q.
  ArapSoftConstraints soft;
  soft.vertices = fixed_.tail(fixed_.size() - low_);
  soft.vertex_weights = Eigen::VectorXd::Constant(soft.vertices.size(), 10.0);
  ArapData soft_data = arap_precompute(mesh_.V, mesh_.F, one_end, soft);
  const Eigen::MatrixXd soft_targets = targets_.bottomRows(fixed_.size() - low_);
  Eigen::MatrixXd U_soft = mesh_.V;
  arap_solve(soft_data, targets, soft_targets, U_soft, options_);
  ASSERT_TRUE(soft_data.free_rows);
  const Eigen::VectorXd heavier = Eigen::VectorXd::Constant(soft.vertices.size(), 100.0);
  arap_set_soft_weights(soft_data, heavier, Eigen::VectorXd());
  EXPECT_FALSE(soft_data.free_rows);
  soft.vertex_weights = heavier;
  ArapData soft_fresh = arap_precompute(mesh_.V, mesh_.F, one_end, soft);
  Eigen::MatrixXd U_set = mesh_.V, U_new = mesh_.V;
  arap_solve(soft_data, targets, soft_targets, U_set, options_);
  arap_solve(soft_fresh, targets, soft_targets, U_new, options_);
  // The refactorization reuses the symbolic analysis, the fresh one makes its own: rounding apart
  // (1e-12 of the unit-size patch).
  EXPECT_LE((U_set - U_new).cwiseAbs().maxCoeff(), 1e-12);
}

} // namespace
} // namespace iarap
