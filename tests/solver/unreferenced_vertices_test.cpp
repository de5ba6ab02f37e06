// Vertices used by no face (common in real files: the Stanford bunny, the teapot as distributed) are kept:
// they have no energy, so arap_precompute pins them where the initial guess puts them instead of reporting a
// singular component, and the rest of the mesh deforms as without them.
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

namespace iarap {
namespace {

class UnreferencedVertices : public test::SingleThreadTest {};

TEST_F(UnreferencedVertices, AreKeptInPlaceAndChangeNothingElse) {
  const test::SolverMesh m = test::bumpy_patch(10);
  const Eigen::Index n = m.V.rows();
  Eigen::MatrixXd V(n + 2, 3); // two stray points, one far outside the patch
  V << m.V, Eigen::RowVector3d(0.5, 0.5, 3.0), Eigen::RowVector3d(-40.0, 7.0, 1.0);
  const Eigen::VectorXi fixed = test::to_vector(test::axis_band(m.V, 0, 0.15, -1));
  const Eigen::VectorXi handle = test::to_vector(test::axis_band(m.V, 0, 0.15, +1));
  Eigen::VectorXi constrained(fixed.size() + handle.size());
  constrained << fixed, handle;
  Eigen::MatrixXd targets = test::rows_of(m.V, constrained);
  for (Eigen::Index k = fixed.size(); k < constrained.size(); ++k) targets(k, 2) += 0.25;
  const double diagonal = test::bbox_diagonal(m.V);
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    ArapOptions options;
    options.method = method;
    ArapData with = arap_precompute(V, m.F, constrained, options);
    EXPECT_EQ(with.pinned.size(), 2) << arap_method_name(method);
    Eigen::MatrixXd U = V;
    arap_solve(with, targets, U);
    ASSERT_EQ(U.rows(), n + 2);
    EXPECT_EQ(U.bottomRows(2), V.bottomRows(2)) << arap_method_name(method); // exactly where they were

    ArapData without = arap_precompute(m.V, m.F, constrained, options);
    Eigen::MatrixXd W = m.V;
    arap_solve(without, targets, W);
    // Same energy, same system on the referenced vertices; only the factor's ordering may differ.
    EXPECT_LT((U.topRows(n) - W).cwiseAbs().maxCoeff(), 1e-9 * diagonal) << arap_method_name(method);
    EXPECT_GT((W - m.V).cwiseAbs().maxCoeff(), 0.1 * diagonal); // it did deform

    // Rest targets: everything stays at rest.
    Eigen::MatrixXd R = V;
    arap_solve(with, test::rows_of(V, constrained), R);
    EXPECT_LT((R - V).cwiseAbs().maxCoeff(), 1e-9 * diagonal) << arap_method_name(method);
  }
}

} // namespace
} // namespace iarap
