// Newton's warm start across arap_solve calls (ArapSolveOptions::newton_trust_radius and
// newton_reference_gradient, filled from ArapReport): a solve cut in two calls that hand the state on
// runs the iterates of one call (up to rounding), which a fresh restart does not.
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <limits>

namespace iarap {
namespace {

class NewtonWarmStart : public test::SingleThreadTest {
protected:
  void SetUp() override {
    test::SingleThreadTest::SetUp();
    mesh_ = test::bumpy_patch(12);
    const Eigen::VectorXi low = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, -1));
    const Eigen::VectorXi high = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, +1));
    fixed_.resize(low.size() + high.size());
    fixed_ << low, high;
    targets_ = test::rows_of(mesh_.V, fixed_);
    // A large edit, so that the trust radius changes over the iterations.
    for (Eigen::Index k = low.size(); k < fixed_.size(); ++k) targets_(k, 2) += 0.6;
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

} // namespace
} // namespace iarap
