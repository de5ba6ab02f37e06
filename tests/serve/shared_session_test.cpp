// The session as the HTTP workers share it (app/serve/shared_session.h): a solve asked to refine goes on
// in the background and publishes refined frames of its generation; a caller of the session preempts it.
#include "../../app/serve/shared_session.h" // the tool's sources: tests/ is on the include path, app/ is not
#include "serve_test_meshes.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace {

using iarap::serve::Session;
using iarap::serve::SessionFrame;
using iarap::serve::SharedSession;
using iarap::serve::SolveRequest;
using iarap::test::grid_column;

constexpr int shared_columns = 8, shared_rows = 3;

// A strip fixed at its left column, its right column the handle.
void load_strip(SharedSession& shared) {
  shared.change([](Session& s) {
    s.load_mesh("strip", iarap::test::grid_mesh(shared_columns, shared_rows, 2.0, 0.3));
    s.set_constraints(grid_column(shared_columns, shared_rows, 0),
                      grid_column(shared_columns, shared_rows, shared_columns));
  });
}

// The handle's rest positions raised by dz.
Eigen::MatrixXd raised_handle(const SharedSession& shared, double dz) {
  Eigen::MatrixXd targets = shared.read([](const Session& s) {
    const Eigen::MatrixXd V = s.snapshot(std::nullopt).V;
    Eigen::MatrixXd rows_out(s.handle().size(), 3);
    for (Eigen::Index k = 0; k < s.handle().size(); ++k) rows_out.row(k) = V.row(s.handle()[k]);
    return rows_out;
  });
  targets.col(2).array() += dz;
  return targets;
}

} // namespace

TEST(ServeSharedSession, RefinesInTheBackgroundAndYields) {
  SharedSession shared;
  load_strip(shared);
  SolveRequest request;
  request.solve.max_iterations = 1; // the answer stops early; the refinement goes on
  request.refine_iterations = 1000;
  Eigen::MatrixXd targets = raised_handle(shared, 0.5);
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

// A solve that comes while a refinement runs ends it at the iteration in progress: the answer says it
// preempted a refinement and waited for at most that one iteration, however long the machine took.
TEST(ServeSharedSession, ASolveWaitsForOneRefinementIterationAtMost) {
  SharedSession shared;
  load_strip(shared);
  SolveRequest request;
  request.solve.max_iterations = 1;
  request.solve.tolerance = -1; // no energy rule, no gradient rule: the refinement runs to its limit
  request.solve.gradient_tolerance = 0;
  request.refine_accelerator = iarap::ArapAccelerator::None;
  request.refine_iterations = 1000000; // seconds of plain iterations on the strip: it runs when preempted
  Eigen::MatrixXd targets = raised_handle(shared, 0.5);
  request.handle_targets = targets;
  const iarap::serve::SolveResult answer = shared.solve(request);
  ASSERT_TRUE(answer.refining);
  const std::shared_ptr<const SessionFrame> refined =
      shared.frames().wait_newer(answer.sequence, std::chrono::seconds(10));
  ASSERT_TRUE(refined) << "no refinement frame within 10 s";
  ASSERT_TRUE(refined->refining) << refined->error << " after " << refined->iterations
                                 << " iterations, converged " << refined->converged;
  EXPECT_GE(shared.refinement_iterations(), static_cast<std::uint64_t>(refined->iterations));

  targets.col(2).array() += 0.1;
  request.handle_targets = targets;
  request.refine_iterations = 0;
  // Into the next chunk (100 ms, started at once after the frame): a caller that queues between two
  // chunks waits for none, which would not test the preemption inside a chunk (without it: 2201 iterations).
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const iarap::serve::SolveResult preempting = shared.solve(request);
  EXPECT_TRUE(preempting.refinement_preempted);
  EXPECT_LE(preempting.refinement_iterations_waited, 1) << "waited " << preempting.wait_ms << " ms";
  EXPECT_FALSE(shared.read([](const Session& s) { return s.refining(); }));
}
