// Why arap_solve stops (ArapReport::stop_reason): each rule of ArapSolveOptions, the wall-clock budget
// included.
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace iarap {
namespace {

class Stopping : public test::SingleThreadTest {
protected:
  void SetUp() override {
    test::SingleThreadTest::SetUp();
    mesh_ = test::bumpy_patch(12);
    fixed_ = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, -1));
    const Eigen::VectorXi handle = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, +1));
    Eigen::VectorXi all(fixed_.size() + handle.size());
    all << fixed_, handle;
    fixed_ = all;
    targets_ = test::rows_of(mesh_.V, fixed_);
    for (Eigen::Index k = fixed_.size() - handle.size(); k < fixed_.size(); ++k) targets_(k, 2) += 0.3;
  }
  ArapReport solve(const ArapSolveOptions& options) {
    ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
    Eigen::MatrixXd U = mesh_.V;
    return arap_solve(data, targets_, U, options);
  }
  test::SolverMesh mesh_;
  Eigen::VectorXi fixed_;
  Eigen::MatrixXd targets_;
};

// A budget every iteration outlasts (one nanosecond) stops after the first iteration, whatever the limit.
TEST_F(Stopping, TimeBudgetStopsAfterTheIterationThatEndsPastIt) {
  for (ArapAccelerator accelerator :
       {ArapAccelerator::None, ArapAccelerator::Anderson, ArapAccelerator::Lbfgs, ArapAccelerator::Newton}) {
    ArapSolveOptions options;
    options.accelerator = accelerator;
    options.max_iterations = 100;
    options.tolerance = -1;
    options.time_budget_ms = 1e-6;
    const ArapReport report = solve(options);
    EXPECT_EQ(report.iterations, 1) << arap_accelerator_name(accelerator);
    EXPECT_EQ(report.stop_reason, ArapStopReason::TimeBudget);
    EXPECT_FALSE(report.converged);
    EXPECT_GE(report.elapsed_ms.back(), options.time_budget_ms);
  }
}

TEST_F(Stopping, EachRuleNamesItself) {
  ArapSolveOptions options;
  options.max_iterations = 3;
  options.tolerance = -1;
  EXPECT_EQ(solve(options).stop_reason, ArapStopReason::MaxIterations);
  options.max_iterations = 500;
  options.tolerance = 1e-3;
  const ArapReport energy = solve(options);
  EXPECT_EQ(energy.stop_reason, ArapStopReason::EnergyTolerance);
  EXPECT_TRUE(energy.converged);
  EXPECT_LT(energy.iterations, 500);
  options.tolerance = -1;
  options.gradient_tolerance = 1e-2;
  EXPECT_EQ(solve(options).stop_reason, ArapStopReason::GradientTolerance);
  options.gradient_tolerance = 0;
  options.on_iteration = [](const ArapReport& r) { return r.iterations < 2; };
  const ArapReport callback = solve(options);
  EXPECT_EQ(callback.stop_reason, ArapStopReason::Callback);
  EXPECT_EQ(callback.iterations, 2);
  // A generous budget changes nothing: the same iterates as without it.
  options.on_iteration = nullptr;
  options.max_iterations = 5;
  options.time_budget_ms = 1e9;
  EXPECT_EQ(solve(options).stop_reason, ArapStopReason::MaxIterations);
  EXPECT_EQ(arap_stop_reason_name(ArapStopReason::TimeBudget), "time_budget");
}

// on_iteration sees each iteration, also the one a rule of the options ends the solve on (the viewer's
// refinement judges its own stopping rule there: with chunks one iteration long it never saw one).
TEST_F(Stopping, CallbackSeesEveryIterationTheLastIncluded) {
  ArapSolveOptions options;
  std::vector<int> seen;
  options.on_iteration = [&seen](const ArapReport& r) {
    seen.push_back(r.iterations);
    return true;
  };
  const auto check = [&](ArapStopReason reason) {
    seen.clear();
    const ArapReport report = solve(options);
    EXPECT_EQ(report.stop_reason, reason);
    ASSERT_EQ(seen.size(), static_cast<std::size_t>(report.iterations));
    for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], static_cast<int>(k) + 1);
  };
  for (ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    options.accelerator = accelerator;
    options.max_iterations = 100;
    options.tolerance = -1;
    options.time_budget_ms = 1e-6;
    check(ArapStopReason::TimeBudget);
    options.time_budget_ms = 0;
    options.tolerance = 1e-3;
    check(ArapStopReason::EnergyTolerance);
    options.tolerance = -1;
    options.max_iterations = 4;
    check(ArapStopReason::MaxIterations);
  }
  // A callback that says stop on the iteration a rule ends leaves that rule's name.
  options.accelerator = ArapAccelerator::None;
  options.max_iterations = 100;
  options.time_budget_ms = 1e-6;
  options.on_iteration = [](const ArapReport&) { return false; };
  EXPECT_EQ(solve(options).stop_reason, ArapStopReason::TimeBudget);
}

TEST_F(Stopping, BadBudgetIsAnInputError) {
  for (double budget :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    ArapSolveOptions options;
    options.time_budget_ms = budget;
    EXPECT_THROW(solve(options), InputError) << budget;
  }
}

} // namespace
} // namespace iarap
