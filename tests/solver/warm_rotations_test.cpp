// ArapSolveOptions::warm_start_rotations: a solve that starts its first rotation fits from the rotations an
// earlier solve left in data.R computes the same rotations to rounding (the polar fit is unique), so its
// iterates are a cold solve's to rounding; where it does not apply (rotation smoothing, no rotations kept)
// it is the cold solve bit for bit.
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace iarap {
namespace {

class WarmRotations : public test::SingleThreadTest {
protected:
  void SetUp() override {
    test::SingleThreadTest::SetUp();
    mesh_ = test::bumpy_patch(12);
    const Eigen::VectorXi low = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, -1));
    const Eigen::VectorXi high = test::to_vector(test::axis_band(mesh_.V, 0, 0.15, +1));
    fixed_.resize(low.size() + high.size());
    fixed_ << low, high;
    first_ = test::rows_of(mesh_.V, fixed_);
    second_ = first_;
    // Two updates of a drag: the high band lifted by 0.3, then by 0.35 (the patch is about 1 across).
    for (Eigen::Index k = low.size(); k < fixed_.size(); ++k) {
      first_(k, 2) += 0.3;
      second_(k, 2) += 0.35;
    }
    options_.tolerance = -1;
    options_.max_iterations = 5;
  }
  // The first update solved on data (leaving its rotations in data.R); U its result.
  Eigen::MatrixXd first_update(ArapData& data) const {
    Eigen::MatrixXd U = mesh_.V;
    arap_solve(data, first_, U, options_);
    return U;
  }
  test::SolverMesh mesh_;
  Eigen::VectorXi fixed_;
  Eigen::MatrixXd first_, second_;
  ArapSolveOptions options_;
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
  // Rotation smoothing fits all rotations at once from the covariances: its local step starts cold.
  ArapSolveOptions smooth = options_;
  smooth.rotation_smoothing = 0.1;
  ArapSolveOptions smooth_warm = smooth;
  smooth_warm.warm_start_rotations = true;
  Eigen::MatrixXd U_warm = start, U_cold = start;
  const ArapReport w = arap_solve(data, second_, U_warm, smooth_warm);
  const ArapReport c = arap_solve(data, second_, U_cold, smooth);
  EXPECT_EQ(w.energies, c.energies);
  EXPECT_TRUE(U_warm == U_cold);
  // No rotations kept (a fresh data, or one whose rotations were cleared): nothing to start from.
  data.R.clear();
  ArapSolveOptions plain_warm = options_;
  plain_warm.warm_start_rotations = true;
  Eigen::MatrixXd V_warm = start, V_cold = start;
  const ArapReport pw = arap_solve(data, second_, V_warm, plain_warm);
  const ArapReport pc = arap_solve(data, second_, V_cold, options_);
  EXPECT_EQ(pw.energies, pc.energies);
  EXPECT_TRUE(V_warm == V_cold);
}

} // namespace
} // namespace iarap
