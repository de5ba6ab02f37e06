// Newton's warm start across arap_solve calls (ArapSolveOptions::newton_trust_radius and
// newton_reference_gradient, filled from ArapReport): a solve cut in two calls that hand the state on
// runs the iterates of one call (up to rounding), which a fresh restart does not. Its yielding between CG
// steps (should_yield), and the rotations' warm start (warm_start_rotations).
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <limits>
#include <utility>

namespace iarap {
namespace {

class NewtonWarmStart : public test::SingleThreadTest {
protected:
  void SetUp() override {
    test::SingleThreadTest::SetUp();
    mesh_ = test::bumpy_patch(12);
    Eigen::Index low = 0;
    fixed_ = test::both_ends(mesh_.V, 0, 0.15, low);
    targets_ = test::rows_of(mesh_.V, fixed_);
    // A large edit, so that the trust radius changes over the iterations.
    for (Eigen::Index k = low; k < fixed_.size(); ++k) targets_(k, 2) += 0.6;
    options_.accelerator = ArapAccelerator::Newton;
    options_.tolerance = -1;
  }
  test::SolverMesh mesh_;
  Eigen::VectorXi fixed_;
  Eigen::MatrixXd targets_;
  ArapSolveOptions options_;
};

TEST_F(NewtonWarmStart, TwoCallsHandingTheStateOnEqualOneCall) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  Eigen::MatrixXd whole = mesh_.V;
  options_.max_iterations = 6;
  const ArapReport one = arap_solve(data, targets_, whole, options_);
  ASSERT_GT(one.newton_trust_radius, 0);
  ASSERT_GT(one.newton_reference_gradient, 0);

  Eigen::MatrixXd cut = mesh_.V;
  options_.max_iterations = 3;
  const ArapReport first = arap_solve(data, targets_, cut, options_);
  Eigen::MatrixXd fresh = cut;
  ArapSolveOptions warm = options_;
  warm.max_iterations = 3;
  warm.newton_trust_radius = first.newton_trust_radius;
  warm.newton_reference_gradient = first.newton_reference_gradient;
  const ArapReport second = arap_solve(data, targets_, cut, warm);
  // The second call recomputes the energy and gradient at the same positions, and CG then sees the same
  // radius and forcing term: the same path up to rounding (measured 5e-15 on this unit-size patch; 1e-12
  // leaves room for other compilers), where a fresh restart moves the shape by 1e-3.
  EXPECT_LE((cut - whole).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(second.energies.back(), one.energies.back(), 1e-12 * one.energies.back());
  EXPECT_NEAR(second.newton_trust_radius, one.newton_trust_radius, 1e-9 * one.newton_trust_radius);

  // Restarted fresh (radius from the plain step, reference ||g|| of the restart) the path differs.
  ArapSolveOptions cold = options_;
  cold.max_iterations = 3;
  arap_solve(data, targets_, fresh, cold);
  EXPECT_GT((fresh - whole).cwiseAbs().maxCoeff(), 1e-6);
}

// ArapSolveOptions::should_yield ends an iteration's CG after its current step: always true, every
// iteration takes one CG step, which is CG limited to one step (window 1) bit for bit; never true, nothing
// changes.
TEST_F(NewtonWarmStart, YieldingEndsCgAfterTheCurrentStep) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  options_.max_iterations = 4;
  const auto solve = [&](const ArapSolveOptions& options) {
    Eigen::MatrixXd U = mesh_.V;
    const ArapReport report = arap_solve(data, targets_, U, options);
    return std::make_pair(U, report);
  };
  ArapSolveOptions yielding = options_, one_step = options_, never = options_;
  int asked = 0;
  yielding.should_yield = [&asked] { return ++asked > 0; };
  one_step.window = 1;
  never.should_yield = [] { return false; };
  const auto [U_yield, yield] = solve(yielding);
  const auto [U_one, one] = solve(one_step);
  const auto [U_never, not_yielded] = solve(never);
  const auto [U_plain, plain] = solve(options_);
  EXPECT_TRUE(U_yield == U_one);
  EXPECT_EQ(yield.energies, one.energies);
  EXPECT_EQ(yield.solves, one.solves);
  EXPECT_GT(asked, 0);
  EXPECT_TRUE(U_never == U_plain);
  EXPECT_EQ(not_yielded.energies, plain.energies);
  // The default window takes more CG steps per iteration: the check is not vacuous.
  EXPECT_GT(plain.solves, one.solves);
}

TEST_F(NewtonWarmStart, OtherAcceleratorsReportNoState) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  for (ArapAccelerator accelerator :
       {ArapAccelerator::None, ArapAccelerator::Anderson, ArapAccelerator::Lbfgs}) {
    Eigen::MatrixXd U = mesh_.V;
    options_.accelerator = accelerator;
    options_.max_iterations = 3;
    const ArapReport report = arap_solve(data, targets_, U, options_);
    EXPECT_EQ(report.newton_trust_radius, 0) << arap_accelerator_name(accelerator);
    EXPECT_EQ(report.newton_reference_gradient, 0);
  }
}

TEST_F(NewtonWarmStart, NegativeOrNonFiniteStateIsRefusedByName) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  Eigen::MatrixXd U = mesh_.V;
  for (const double bad :
       {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    ArapSolveOptions options = options_;
    options.newton_trust_radius = bad;
    EXPECT_THROW(
        try { arap_solve(data, targets_, U, options); } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("newton_trust_radius"), std::string::npos) << e.what();
          throw;
        },
        InputError);
    options = options_;
    options.newton_reference_gradient = bad;
    EXPECT_THROW(arap_solve(data, targets_, U, options), InputError);
  }
}

// ArapSolveOptions::warm_start_rotations: a solve that starts its first rotation fits from the rotations an
// earlier solve left in data.R computes the same rotations to rounding (the polar fit is unique), so its
// iterates are a cold solve's to rounding; where it does not apply (rotation smoothing, no rotations kept)
// it is the cold solve bit for bit. Two updates of a drag: the high band lifted half way, then all the way.
class WarmRotations : public NewtonWarmStart {
protected:
  void SetUp() override {
    NewtonWarmStart::SetUp();
    second_ = targets_;
    first_ = test::rows_of(mesh_.V, fixed_);
    first_ += 0.5 * (second_ - first_);
    options_.accelerator = ArapAccelerator::None;
    options_.max_iterations = 5;
  }
  // The first update solved on data (leaving its rotations in data.R); U its result.
  Eigen::MatrixXd first_update(ArapData& data) const {
    Eigen::MatrixXd U = mesh_.V;
    arap_solve(data, first_, U, options_);
    return U;
  }
  Eigen::MatrixXd first_, second_;
};

TEST_F(WarmRotations, EqualsTheColdSolveToRounding) {
  for (const ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
    const Eigen::MatrixXd start = first_update(data);
    ASSERT_EQ(data.R.size(), static_cast<size_t>(data.elements.num_cells));
    ArapSolveOptions warm = options_, cold = options_;
    warm.accelerator = cold.accelerator = accelerator;
    warm.warm_start_rotations = true;
    Eigen::MatrixXd U_warm = start, U_cold = start;
    const ArapReport w = arap_solve(data, second_, U_warm, warm); // from the first update's rotations
    const ArapReport c = arap_solve(data, second_, U_cold, cold);
    ASSERT_EQ(w.energies.size(), c.energies.size());
    // Rotations equal to a few ulps make energies equal to a few ulps; five iterations amplify the
    // difference by at most the iteration's Lipschitz constant (below 1 for the plain step) per step:
    // 1e-12 relative is a thousand times that.
    EXPECT_NEAR(w.initial_energy, c.initial_energy, 1e-12 * c.initial_energy);
    for (size_t k = 0; k < c.energies.size(); ++k)
      EXPECT_NEAR(w.energies[k], c.energies[k], 1e-12 * c.energies[k]) << "iteration " << k + 1;
    EXPECT_LE((U_warm - U_cold).cwiseAbs().maxCoeff(), 1e-10 * test::bbox_diagonal(mesh_.V))
        << arap_accelerator_name(accelerator);
  }
}

TEST_F(WarmRotations, IsTheColdSolveBitForBitWhereItDoesNotApply) {
  ArapData data = arap_precompute(mesh_.V, mesh_.F, fixed_);
  const Eigen::MatrixXd start = first_update(data);
  // The second update with options, warm then cold: the same bits.
  const auto expect_same_bits = [&](const ArapSolveOptions& options, const char* what) {
    ArapSolveOptions warm = options;
    warm.warm_start_rotations = true;
    Eigen::MatrixXd U_warm = start, U_cold = start;
    const ArapReport w = arap_solve(data, second_, U_warm, warm);
    const ArapReport c = arap_solve(data, second_, U_cold, options);
    EXPECT_EQ(w.energies, c.energies) << what;
    EXPECT_TRUE(U_warm == U_cold) << what;
  };
  // Rotation smoothing fits all rotations at once from the covariances: its local step starts cold.
  ArapSolveOptions smooth = options_;
  smooth.rotation_smoothing = 0.1;
  expect_same_bits(smooth, "rotation smoothing");
  // No rotations kept (a fresh data, or one whose rotations were cleared): nothing to start from.
  data.R.clear();
  expect_same_bits(options_, "no rotations kept");
}

} // namespace
} // namespace iarap
