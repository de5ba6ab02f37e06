// The server's session model (app/serve/session.h) without HTTP: load, constraints, solve, undo,
// refinement, and the errors each refuses with.
#include "../../app/serve/session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <string>

namespace {

using iarap::InputError;
using iarap::serve::Session;
using iarap::serve::SessionConflict;
using iarap::serve::SolveProgress;
using iarap::serve::SolveRequest;
using iarap::test::contains;
using iarap::test::grid_column;
using iarap::test::grid_mesh;
using iarap::test::rows_of;

constexpr int session_columns = 8, session_rows = 3;
constexpr double session_width = 2.0, session_lift = 0.3;

// A curved strip (z = 0.3 x^2 / 4), left column fixed, right column the handle.
Session loaded_session() {
  Session session;
  session.load_mesh("strip", grid_mesh(session_columns, session_rows, session_width, session_lift));
  session.set_constraints(grid_column(session_columns, session_rows, 0),
                          grid_column(session_columns, session_rows, session_columns));
  return session;
}

// The handle moved up by `up` in z.
SolveRequest lift_request(const Session& session, double up, int iterations) {
  const Eigen::MatrixXd V = session.snapshot(std::nullopt).V;
  SolveRequest request;
  request.solve.max_iterations = iterations;
  Eigen::MatrixXd targets = rows_of(V, session.handle());
  targets.col(2).array() += up;
  request.handle_targets = targets;
  return request;
}

} // namespace

TEST(ServeSession, SolveMovesTheShapeTowardTheTargets) {
  Session session = loaded_session();
  const double up = 0.5;
  const SolveRequest request = lift_request(session, up, 50);
  SolveProgress progress;
  const iarap::serve::SolveResult result = session.solve(request, progress);
  const Eigen::MatrixXd V = session.snapshot(std::nullopt).V;
  const Eigen::MatrixXd U = session.snapshot(request.method).V;
  const double diagonal = session.mesh_summary().bbox_diagonal;

  // Hard constraints: the handle at its targets and the fixed column at rest, to the solve's rounding
  // (a few ulps of the coordinates, far below 1e-12 of the diagonal).
  EXPECT_LE((rows_of(U, session.handle()) - *request.handle_targets).cwiseAbs().maxCoeff(), 1e-12 * diagonal);
  EXPECT_LE((rows_of(U, session.fixed()) - rows_of(V, session.fixed())).cwiseAbs().maxCoeff(),
            1e-12 * diagonal);
  // The free columns follow: each rises by a positive amount below the handle's (a bent strip between a
  // fixed and a lifted end), more the nearer it is to the handle.
  double previous = 0;
  for (int i = 1; i < session_columns; ++i) {
    const Eigen::VectorXi column = grid_column(session_columns, session_rows, i);
    const double rise = (rows_of(U, column) - rows_of(V, column)).col(2).mean();
    EXPECT_GT(rise, previous) << "column " << i;
    EXPECT_LT(rise, up) << "column " << i;
    previous = rise;
  }
  // The energy decreased from the initial guess (the rest shape with the handle moved) and the result is
  // the session's published state.
  ASSERT_FALSE(result.report.energies.empty());
  EXPECT_LT(result.report.energies.back(), result.report.initial_energy);
  EXPECT_EQ(result.positions.size(), static_cast<std::size_t>(3 * U.rows()));
  EXPECT_FALSE(result.planar); // a curved strip
  EXPECT_FALSE(progress.running.load());
  EXPECT_GT(progress.iteration.load(), 0); // published while it ran
}

TEST(ServeSession, BadVertexIndexIsNamedAndChangesNothing) {
  Session session = loaded_session();
  const int vertex_count = session.mesh_summary().vertices;
  const Eigen::VectorXi fixed_before = session.fixed();
  const int revision_before = session.revision();
  Eigen::VectorXi handle(2);
  handle << 3, vertex_count;
  try {
    session.set_constraints(fixed_before, handle);
    FAIL() << "an index past the mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "handle[1] = " + std::to_string(vertex_count))) << e.what();
    EXPECT_TRUE(contains(e.what(), "the mesh has " + std::to_string(vertex_count) + " vertices")) << e.what();
  }
  EXPECT_EQ(session.fixed(), fixed_before);
  EXPECT_EQ(session.revision(), revision_before);

  Eigen::VectorXi both(1);
  both << fixed_before[0];
  try {
    session.set_constraints(fixed_before, both);
    FAIL() << "a vertex in both sets was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "handle[0] = " + std::to_string(both[0]) + " repeats fixed[0]"))
        << e.what();
  }
}

TEST(ServeSession, WrongTargetCountIsRefused) {
  Session session = loaded_session();
  SolveRequest request;
  request.handle_targets = Eigen::MatrixXd::Zero(2, 3); // the handle has session_rows + 1 = 4 vertices
  SolveProgress progress;
  const std::uint64_t generation = session.generation();
  try {
    session.solve(request, progress);
    FAIL() << "two targets for four handle vertices were accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "handle_targets has 6 numbers; expected 3 x 4")) << e.what();
  }
  EXPECT_EQ(session.generation(), generation); // refused before anything changed
  EXPECT_EQ(session.snapshot(request.method).V, session.snapshot(std::nullopt).V);
}

TEST(ServeSession, ConflictsWithoutMeshOrConstraints) {
  Session empty;
  EXPECT_FALSE(empty.has_mesh());
  EXPECT_THROW(empty.mesh_summary(), SessionConflict);
  EXPECT_THROW(empty.set_constraints(Eigen::VectorXi(), Eigen::VectorXi()), SessionConflict);

  Session session;
  session.load_mesh("strip", grid_mesh(session_columns, session_rows, session_width));
  SolveProgress progress;
  EXPECT_THROW(session.solve(SolveRequest(), progress), SessionConflict);
  EXPECT_THROW(session.restore_constraints(7), SessionConflict);
}

TEST(ServeSession, UndoBringsBackTheSetsAndAnchors) {
  Session session = loaded_session();
  const int first = session.revision();
  SolveProgress progress;
  session.solve(lift_request(session, 0.4, 20), progress);
  // A new handle on the deformed shape: its anchors are where the solve left it.
  session.set_constraints(grid_column(session_columns, session_rows, 0),
                          grid_column(session_columns, session_rows, session_columns / 2));
  EXPECT_GT(session.revision(), first);
  session.restore_constraints(first);
  EXPECT_EQ(session.handle(), grid_column(session_columns, session_rows, session_columns));
  // The restored anchors are the rest positions: a solve without targets goes back to the rest shape.
  SolveRequest back;
  back.solve.max_iterations = 200;
  back.solve.tolerance = 1e-14;
  session.solve(back, progress);
  const double diagonal = session.mesh_summary().bbox_diagonal;
  EXPECT_LE((session.snapshot(back.method).V - session.snapshot(std::nullopt).V).cwiseAbs().maxCoeff(),
            1e-6 *
                diagonal); // the rest shape is the minimum (E = 0); 200 Newton steps reach it far below 1e-6
}

TEST(ServeSession, RefinementGoesOnAndStops) {
  Session session = loaded_session();
  SolveRequest request = lift_request(session, 0.5, 1);
  request.refine_iterations = 100;
  SolveProgress progress;
  const iarap::serve::SolveResult answer = session.solve(request, progress);
  ASSERT_TRUE(answer.refining);
  ASSERT_TRUE(session.refining());
  const double answered = answer.report.energies.back();
  // One chunk that may run one iteration, then preempted: it goes on from the answer, never up.
  int calls = 0;
  const iarap::serve::SessionFrame frame = session.refine_chunk(1e6, [&calls] { return ++calls < 2; });
  EXPECT_TRUE(frame.refined);
  EXPECT_EQ(frame.generation, answer.generation);
  EXPECT_GE(frame.iterations, 1);
  EXPECT_LE(frame.energy, answered);
  EXPECT_TRUE(frame.error.empty()) << frame.error;
  const std::optional<iarap::serve::SessionFrame> stopped = session.stop_refinement();
  ASSERT_TRUE(stopped.has_value());
  EXPECT_FALSE(session.refining());
  EXPECT_NEAR(stopped->energy, frame.energy, 1e-12 * std::abs(frame.energy)); // same U, same energy
  EXPECT_FALSE(session.stop_refinement().has_value());
}
