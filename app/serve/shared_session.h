// The Session (session.h) as the HTTP workers share it, and the background refiner that goes on after a
// solve's answer: one mutex, and a thread that solves the pending refinement job in chunks while nobody
// else wants the session.
//
// A solve asked to refine keeps going toward its targets after answering, in chunks of about
// refine_frame_ms that each publish a frame (FrameBoard). Every call that takes the session mutex preempts
// it at the next iteration boundary: the chunk's callback sees the caller waiting and stops, the last
// finished iterate is kept, and the caller gets the mutex.
#pragma once
#include "fit_runner.h"
#include "frame_board.h"
#include "session.h"
#include "solve_progress.h"

#include "iarap/core/stopwatch.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <utility>

namespace iarap::serve {

class SharedSession {
public:
  SharedSession();  // starts the refinement thread
  ~SharedSession(); // stops it at its next iteration boundary
  SharedSession(const SharedSession&) = delete;
  SharedSession& operator=(const SharedSession&) = delete;

  // How long one refinement chunk solves before it publishes a frame (the last iteration may run over).
  static constexpr double refine_frame_ms = 100;
  // The refinement starts once no caller has held the session for this long, so that it does not cost a
  // drag, whose next update comes within a frame of the pointer (16 ms at 60 Hz) plus a round trip.
  static constexpr double refine_delay_ms = 40;

  // f(const Session&) under the session mutex (preempting the refinement); returns what f returns, which
  // must not refer into the session.
  template <class F> auto read(F&& f) const {
    const SessionLock lock(*this);
    return std::forward<F>(f)(static_cast<const Session&>(session_));
  }
  // f(Session&) under the session mutex: for changes other than a solve (load, constraints, reset...).
  template <class F> auto change(F&& f) {
    const SessionLock lock(*this);
    return std::forward<F>(f)(session_);
  }

  // Session::solve, timed from the call (wait_ms), with its answer published on frames() (sequence); a
  // refinement it leaves starts once this call released the session.
  SolveResult solve(const SolveRequest& request);
  // Ends the background refinement (its last iterate stays) and publishes a frame saying so; false when
  // none was running.
  bool stop_refinement();

  // The refinement iterations ended since the session was made (every job's, counted as they end).
  std::uint64_t refinement_iterations() const { return refine_iterations_.load(); }
  // Read without the session mutex (see SolveProgress).
  SolveProgress& progress() { return progress_; }
  // The answers, refinement and fit frames, read without the session mutex.
  FrameBoard& frames() { return frames_; }
  // The fit of the rest mesh to the loaded target, on its own thread (fit_runner.h).
  FitRunner& fits() { return fits_; }

private:
  // The session mutex, taken so that a running refinement chunk stops at its next iteration boundary:
  // waiting_ counts the callers queued for the mutex; the refinement thread is woken on release.
  class SessionLock {
  public:
    explicit SessionLock(const SharedSession& shared);
    ~SessionLock();
    SessionLock(const SessionLock&) = delete;
    SessionLock& operator=(const SessionLock&) = delete;

    // The refinement iterations that ended while this caller queued: at most the one it interrupted.
    int refinement_iterations_waited() const;

  private:
    const SharedSession& shared_;
    std::uint64_t refine_iterations_at_arrival_;
    std::unique_lock<std::mutex> lock_;
  };

  void refine_in_background();

  Session session_;
  mutable std::mutex mutex_;
  SolveProgress progress_;
  FrameBoard frames_;
  mutable std::atomic<int> waiting_{0};
  std::atomic<std::uint64_t> refine_iterations_{0}; // every refinement iteration ended, counted as it ends
  mutable std::condition_variable refine_wake_;
  mutable Clock::time_point last_release_; // when a caller last released the session (under mutex_)
  std::atomic<bool> stopping_{false};
  std::thread refiner_; // starts once everything above exists
  FitRunner fits_;      // its thread uses everything above
};

} // namespace iarap::serve
