// The session as the HTTP workers share it (app/serve/shared_session.h): a solve asked to refine goes on
// in the background and publishes refined frames of its generation; a caller of the session preempts it.
#include "../../app/serve/shared_session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <chrono>

namespace {

using iarap::serve::Session;
using iarap::serve::SessionFrame;
using iarap::serve::SharedSession;
using iarap::serve::SolveRequest;
using iarap::test::grid_column;

constexpr int shared_columns = 8, shared_rows = 3;

} // namespace

TEST(ServeSharedSession, RefinesInTheBackgroundAndYields) {
  SharedSession shared;
  shared.change([](Session& s) {
    s.load_mesh("strip", iarap::test::grid_mesh(shared_columns, shared_rows, 2.0, 0.3));
    s.set_constraints(grid_column(shared_columns, shared_rows, 0),
                      grid_column(shared_columns, shared_rows, shared_columns));
  });
  SolveRequest request;
  request.solve.max_iterations = 1; // the answer stops early; the refinement goes on
  request.refine_iterations = 1000;
  Eigen::MatrixXd targets = shared.read([](const Session& s) {
    const Eigen::MatrixXd V = s.snapshot(std::nullopt).V;
    Eigen::MatrixXd rows_out(s.handle().size(), 3);
    for (Eigen::Index k = 0; k < s.handle().size(); ++k) rows_out.row(k) = V.row(s.handle()[k]);
    return rows_out;
  });
  targets.col(2).array() += 0.5;
  request.handle_targets = targets;
  const iarap::serve::SolveResult answer = shared.solve(request);
  ASSERT_TRUE(answer.refining);
  EXPECT_GT(answer.sequence, 0u);

  // The answer is on the board at once; a refined frame of the same generation follows within the
  // refinement's start delay (40 ms) and a chunk (100 ms); 10 s leaves room for a loaded machine.
  const std::shared_ptr<const SessionFrame> first =
      shared.frames().wait_newer(0, std::chrono::milliseconds(0));
  ASSERT_TRUE(first);
  EXPECT_EQ(first->sequence, answer.sequence);
  EXPECT_FALSE(first->refined);
  const std::shared_ptr<const SessionFrame> refined =
      shared.frames().wait_newer(answer.sequence, std::chrono::seconds(10));
  ASSERT_TRUE(refined) << "no refinement frame within 10 s";
  EXPECT_TRUE(refined->refined);
  EXPECT_EQ(refined->generation, answer.generation);
  EXPECT_GE(refined->iterations, 1);
  EXPECT_LE(refined->energy, answer.report.energies.back());
  EXPECT_TRUE(refined->error.empty()) << refined->error;

  // A caller gets the session whether or not the refinement still runs, and a reset ends it.
  EXPECT_EQ(shared.read([](const Session& s) { return s.generation(); }), answer.generation);
  shared.change([](Session& s) { s.reset(); });
  EXPECT_FALSE(shared.read([](const Session& s) { return s.refining(); }));
  EXPECT_FALSE(shared.stop_refinement());
}
