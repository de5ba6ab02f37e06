#include "shared_session.h"

#include <chrono>

namespace iarap::serve {
namespace {

// The frame of a solve's answer, numbered when published.
SessionFrame answer_frame(const SolveRequest& request, const SolveResult& result) {
  SessionFrame frame;
  frame.generation = result.generation;
  frame.method = request.method;
  frame.iterations = result.report.iterations;
  frame.energy = last_energy(result.report);
  frame.relative_decrease = last_relative_decrease(result.report);
  frame.tolerance = request.solve.tolerance;
  frame.refining = result.refining;
  frame.converged = result.report.converged;
  frame.positions = result.positions;
  return frame;
}

} // namespace

// Counted after waiting_ is raised: an iteration that ends later was bound to see the caller at its end.
SharedSession::SessionLock::SessionLock(const SharedSession& shared) : shared_(shared) {
  ++shared_.waiting_;
  refine_iterations_at_arrival_ = shared_.refine_iterations_.load();
  lock_ = std::unique_lock<std::mutex>(shared_.mutex_);
  --shared_.waiting_;
}

int SharedSession::SessionLock::refinement_iterations_waited() const {
  return static_cast<int>(shared_.refine_iterations_.load() - refine_iterations_at_arrival_);
}

SharedSession::SessionLock::~SessionLock() {
  shared_.last_release_ = Clock::now();
  lock_.unlock();
  shared_.refine_wake_.notify_one();
}

SharedSession::SharedSession() : refiner_([this] { refine_in_background(); }) {}

SharedSession::~SharedSession() {
  fits_.stop(); // its thread takes the session
  {
    std::lock_guard<std::mutex> lock(mutex_); // stopping_ is read under it by the refiner's wait
    stopping_ = true;
  }
  refine_wake_.notify_one();
  refiner_.join();
  frames_.close();
}

// Waits, with the mutex released, until there is a job, nobody queues for the mutex and the last caller
// left refine_delay_ms ago; then one chunk.
void SharedSession::refine_in_background() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    refine_wake_.wait(lock, [this] { return stopping_ || (session_.refining() && waiting_.load() == 0); });
    if (stopping_) return;
    const auto start = last_release_ + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double, std::milli>(refine_delay_ms));
    if (Clock::now() < start) {
      refine_wake_.wait_until(lock, start); // then everything is checked again
      continue;
    }
    frames_.publish(session_.refine_chunk(
        refine_frame_ms, [this] { return waiting_.load() == 0 && !stopping_.load(); }, // the preemption
        [this] { ++refine_iterations_; }));
  }
}

SolveResult SharedSession::solve(const SolveRequest& request) {
  const auto arrival = Clock::now();
  const SessionLock lock(*this);
  const double wait_ms = ms_since(arrival);
  const int refinement_iterations_waited = lock.refinement_iterations_waited();
  SolveResult result = session_.solve(request, progress_);
  result.wait_ms = wait_ms;
  result.refinement_iterations_waited = refinement_iterations_waited;
  result.sequence = frames_.publish(answer_frame(request, result));
  return result;
}

bool SharedSession::stop_refinement() {
  const SessionLock lock(*this);
  std::optional<SessionFrame> frame = session_.stop_refinement();
  if (!frame) return false;
  frames_.publish(std::move(*frame));
  return true;
}

} // namespace iarap::serve
