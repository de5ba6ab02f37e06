// Soft handles of the server's session (solver_constraints.h): a handle with weights is pulled toward its
// targets instead of being put there, so the shape lags behind them, less as the weight grows.
#include "../../app/serve/session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

namespace {

using iarap::InputError;
using iarap::serve::Session;
using iarap::serve::SolveProgress;
using iarap::serve::SolveRequest;
using iarap::test::contains;
using iarap::test::grid_column;
using iarap::test::grid_mesh;
using iarap::test::rows_of;

constexpr int soft_columns = 8, soft_rows = 3;

// A flat strip bent out of its plane: left column fixed, right column the handle lifted by `up` in z.
Session soft_strip_session() {
  Session session;
  session.load_mesh("strip", grid_mesh(soft_columns, soft_rows, 2.0, 0.3));
  session.set_constraints(grid_column(soft_columns, soft_rows, 0),
                          grid_column(soft_columns, soft_rows, soft_columns));
  return session;
}

// Solved to the minimum: Newton from the previous shape until the gradient falls to 1e-10 of its start.
SolveRequest lift(const Session& session, double up, std::optional<double> weight) {
  SolveRequest request;
  request.solve.max_iterations = 300;
  request.solve.tolerance = 0;
  request.solve.gradient_tolerance = 1e-10;
  Eigen::MatrixXd targets = rows_of(session.snapshot(std::nullopt).V, session.handle());
  targets.col(2).array() += up;
  request.handle_targets = targets;
  if (weight) request.handle_weights = Eigen::VectorXd::Constant(session.handle().size(), *weight);
  return request;
}

// The mean distance of the handle vertices from their targets after solving request.
double handle_lag(Session& session, const SolveRequest& request) {
  SolveProgress progress;
  session.solve(request, progress);
  const Eigen::MatrixXd U = session.snapshot(request.method).V;
  return (rows_of(U, session.handle()) - *request.handle_targets).rowwise().norm().mean();
}

} // namespace

TEST(ServeSoftHandle, LagsBehindItsTargetsLessAsTheWeightGrows) {
  Session session = soft_strip_session();
  const double up = 0.5, diagonal = session.mesh_summary().bbox_diagonal;
  const double hard = handle_lag(session, lift(session, up, std::nullopt));
  EXPECT_LE(hard, 1e-12 * diagonal); // a hard handle sits on its targets

  // One session through the weights (each solve warm-starts from the last: only a refactorization), and
  // the fixed column stays exactly at rest throughout.
  const std::vector<double> weights = {0.01, 0.1, 1, 10, 100};
  std::vector<double> lag;
  for (const double w : weights) lag.push_back(handle_lag(session, lift(session, up, w)));
  const Eigen::MatrixXd U = session.snapshot(SolveRequest().method).V;
  const Eigen::MatrixXd V = session.snapshot(std::nullopt).V;
  EXPECT_LE((rows_of(U, session.fixed()) - rows_of(V, session.fixed())).cwiseAbs().maxCoeff(),
            1e-12 * diagonal);
  std::cout << "soft handle lag / lift:";
  for (std::size_t k = 0; k < weights.size(); ++k) std::cout << " w = " << weights[k] << ": " << lag[k] / up;
  std::cout << " (hard: " << hard / up << ")\n";
  for (std::size_t k = 0; k < weights.size(); ++k) {
    EXPECT_GT(lag[k], 1e-6 * up) << "w = " << weights[k]; // a soft handle does lag
    EXPECT_LT(lag[k], up) << "w = " << weights[k];        // ... but is pulled up at all
    if (k > 0) {
      EXPECT_LT(lag[k], lag[k - 1]) << "w = " << weights[k];
    }
  }
  // For large w the minimizer moves as x_hard + g / (2 w) + O(1 / w^2) (g the hard solution's reaction
  // force): lag * w tends to a constant. From w = 10 to 100 it changes by the O(1 / w) term, under 20%.
  EXPECT_NEAR(lag[4] * weights[4] / (lag[3] * weights[3]), 1.0, 0.2);
}

TEST(ServeSoftHandle, BadWeightsAreNamed) {
  Session session = soft_strip_session();
  SolveProgress progress;
  SolveRequest request = lift(session, 0.5, 1.0);
  request.handle_weights = Eigen::VectorXd::Ones(2);
  try {
    session.solve(request, progress);
    FAIL() << "2 weights for 4 handle vertices were accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "handle_weights has 2 weights; expected one per handle vertex (4)"))
        << e.what();
  }
  request.handle_weights = Eigen::VectorXd::Ones(4);
  (*request.handle_weights)[3] = 0;
  try {
    session.solve(request, progress);
    FAIL() << "a zero weight was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "handle_weights[3]")) << e.what();
  }
}

TEST(ServeSoftHandle, SavedAsSoftLinesOfAConstraintsFile) {
  Session session = soft_strip_session();
  const SolveRequest request = lift(session, 0.5, 3.0);
  const iarap::serve::ConstraintTargets saved = session.constraint_targets(request.method, request);
  EXPECT_EQ(saved.handle.size(), 0);
  EXPECT_EQ(saved.targets.rows(), session.fixed().size());
  ASSERT_EQ(saved.soft.vertices.size(), session.handle().size());
  EXPECT_EQ(saved.soft.vertices, session.handle());
  EXPECT_EQ(saved.soft.vertex_weights, Eigen::VectorXd::Constant(4, 3.0));
  EXPECT_EQ(saved.soft.vertex_targets, *request.handle_targets);
}
