// The drag's prediction (app/serve/drag_motion.h): the scale of the targets' repeated step, the moved
// initial guess, and in the session a drag whose answers lag less with it.
#include "../../app/serve/drag_motion.h"
#include "../../app/serve/session.h"
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using iarap::serve::DragMotion;
using iarap::serve::Session;
using iarap::serve::SolveProgress;
using iarap::serve::SolveRequest;
using iarap::test::grid_column;
using iarap::test::grid_mesh;
using iarap::test::rows_of;

// Two constrained rows moved along x by `x`.
Eigen::MatrixXd targets_at(double x) {
  Eigen::MatrixXd T(2, 3);
  T << x, 0, 0, x, 1, 0;
  return T;
}

Eigen::MatrixXd positions_at(double x) {
  Eigen::MatrixXd U(4, 3);
  U << x, 0, 0, x, 1, 0, 0.5 * x, 2, 0, 0.25 * x, 3, 1;
  return U;
}

} // namespace

TEST(ServeDragMotion, ScaleIsTheRepeatedShareOfTheTargetsStep) {
  DragMotion motion;
  EXPECT_EQ(motion.scale(targets_at(0)), 0); // no answer yet
  motion.record(positions_at(0), targets_at(0));
  EXPECT_EQ(motion.scale(targets_at(1)), 0); // one answer: no step yet
  motion.record(positions_at(0.1), targets_at(0.1));
  // Steps of 0.1 along x: the same step again is s = 1, half of it 0.5, standing still 0, turning back 0
  // (clamped), five steps at once 2 (clamped). Exact to a few ulps of the 0.1's.
  EXPECT_NEAR(motion.scale(targets_at(0.2)), 1, 1e-14);
  EXPECT_NEAR(motion.scale(targets_at(0.15)), 0.5, 1e-14);
  EXPECT_EQ(motion.scale(targets_at(0.1)), 0);
  EXPECT_EQ(motion.scale(targets_at(0.0)), 0);
  EXPECT_EQ(motion.scale(targets_at(0.6)), 2);
  EXPECT_EQ(motion.scale(Eigen::MatrixXd::Zero(3, 3)), 0); // other constrained rows
  // The guess moves by s times the answers' step at every row.
  Eigen::MatrixXd U = positions_at(0.1);
  motion.extrapolate(0.5, U);
  EXPECT_LE((U - positions_at(0.15)).cwiseAbs().maxCoeff(), 1e-15);
  // A step of zero length (the same targets twice) predicts nothing.
  motion.record(positions_at(0.1), targets_at(0.1));
  EXPECT_EQ(motion.scale(targets_at(0.2)), 0);
  motion.clear();
  EXPECT_EQ(motion.scale(targets_at(0.2)), 0);
}

namespace {

constexpr int drag_columns = 10, drag_rows = 3;
constexpr double drag_width = 3.0, drag_lift = 0.2;

// The strip's handle (right column) lifted by `up` in z: one update of a drag of one plain iteration.
SolveRequest drag_update(const Session& session, double up, bool extrapolate) {
  SolveRequest request;
  request.solve.max_iterations = 1;
  request.solve.accelerator = iarap::ArapAccelerator::None;
  request.extrapolate = extrapolate;
  Eigen::MatrixXd targets = rows_of(session.snapshot(std::nullopt).V, session.handle());
  targets.col(2).array() += up;
  request.handle_targets = targets;
  return request;
}

// The last answer's energy after `steps` updates lifting the handle by 0.06 each.
double drag(Session& session, int steps, bool extrapolate, std::vector<double>* scales = nullptr) {
  SolveProgress progress;
  double energy = 0;
  for (int k = 1; k <= steps; ++k) {
    const iarap::serve::SolveResult result =
        session.solve(drag_update(session, 0.06 * k, extrapolate), progress);
    energy = result.report.energies.back();
    if (scales) scales->push_back(result.extrapolation);
  }
  return energy;
}

Session drag_strip_session() {
  Session session;
  session.load_mesh("strip", grid_mesh(drag_columns, drag_rows, drag_width, drag_lift));
  session.set_constraints(grid_column(drag_columns, drag_rows, 0),
                          grid_column(drag_columns, drag_rows, drag_columns));
  return session;
}

} // namespace

TEST(ServeDragMotion, ExtrapolatedDragLagsLess) {
  Session plain = drag_strip_session(), predicted = drag_strip_session();
  const int steps = 20;
  const double plain_energy = drag(plain, steps, false);
  std::vector<double> scales;
  const double predicted_energy = drag(predicted, steps, true, &scales);
  // The first two updates have no step to repeat; then the handle's steps are equal: s = 1 to rounding.
  EXPECT_EQ(scales[0], 0);
  EXPECT_EQ(scales[1], 0);
  for (int k = 2; k < steps; ++k) EXPECT_NEAR(scales[k], 1, 1e-12) << "update " << k;
  // The minimum of the last targets, from the plain drag's answer.
  SolveRequest converge = drag_update(plain, 0.06 * steps, false);
  converge.solve.max_iterations = 500;
  converge.solve.tolerance = 0;
  converge.solve.gradient_tolerance = 1e-10;
  converge.solve.accelerator = iarap::ArapAccelerator::Newton;
  SolveProgress progress;
  const double minimum = plain.solve(converge, progress).report.energies.back();
  const double plain_gap = (plain_energy - minimum) / minimum;
  const double predicted_gap = (predicted_energy - minimum) / minimum;
  std::printf("strip drag, one plain iteration per update: last answer's gap %.3e plain, %.3e extrapolated\n",
              plain_gap, predicted_gap);
  // One plain iteration per update leaves the plain drag far behind; the extrapolated one starts each update
  // one step further and ends well below it (measured: 0.029 against 0.53, 18 times less).
  EXPECT_GT(plain_gap, 0);
  EXPECT_GE(predicted_gap, -1e-12);
  EXPECT_LT(predicted_gap, 0.2 * plain_gap);
}

TEST(ServeDragMotion, NewConstraintsForgetTheMotion) {
  Session session = drag_strip_session();
  drag(session, 3, true);
  session.set_constraints(grid_column(drag_columns, drag_rows, 0),
                          grid_column(drag_columns, drag_rows, drag_columns));
  std::vector<double> scales;
  drag(session, 3, true, &scales); // the first two updates after new constraints predict nothing
  EXPECT_EQ(scales[0], 0);
  EXPECT_EQ(scales[1], 0);
  EXPECT_GT(scales[2], 0);
  // An update that asks for no prediction forgets the motion too.
  SolveProgress progress;
  session.solve(drag_update(session, 0.3, false), progress);
  EXPECT_EQ(session.solve(drag_update(session, 0.36, true), progress).extrapolation, 0);
}

TEST(ServeDragMotion, NewDataForgetsTheHistory) {
  // A flat strip dragged in its plane (a planar solve: 2 unknowns per free vertex) with L-BFGS updates,
  // whose pairs are carried, then lifted out of it: the method's data is built again in 3D, and the
  // carried pairs, of the planar problem's size, must not reach the solver (it refuses a history of
  // another size).
  Session session;
  session.load_mesh("flat strip", grid_mesh(drag_columns, drag_rows, drag_width, 0.0));
  session.set_constraints(grid_column(drag_columns, drag_rows, 0),
                          grid_column(drag_columns, drag_rows, drag_columns));
  const Eigen::MatrixXd rest = rows_of(session.snapshot(std::nullopt).V, session.handle());
  SolveProgress progress;
  SolveRequest request;
  request.solve.max_iterations = 3;
  request.solve.accelerator = iarap::ArapAccelerator::Lbfgs;
  request.extrapolate = true;
  for (int k = 1; k <= 3; ++k) {
    Eigen::MatrixXd targets = rest;
    targets.col(0).array() += 0.05 * k;
    request.handle_targets = targets;
    EXPECT_TRUE(session.solve(request, progress).planar);
  }
  Eigen::MatrixXd lifted = rest;
  lifted.col(0).array() += 0.2;
  lifted.col(2).array() += 0.1;
  request.handle_targets = lifted;
  const iarap::serve::SolveResult result = session.solve(request, progress);
  EXPECT_FALSE(result.planar);
  EXPECT_GT(result.precompute_ms, 0);
  EXPECT_EQ(result.extrapolation, 0);
  EXPECT_LT(result.report.energies.back(), result.report.initial_energy);
}
