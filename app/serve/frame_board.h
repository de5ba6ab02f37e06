// The iterates the session shows: the answer of every solve and the frames of the background refinement
// after it, numbered in the order they were made. GET /api/frame waits here for one newer than the
// client's last. Its own mutex, never the session's: a client waits for frames while the refinement holds
// the session, and a frame is published whole (one finished iterate) or not at all.
#pragma once
#include "iarap/solver/arap_types.h"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace iarap::serve {

// A fit's progress (fit_runner.h): after each registration round, and once at its end.
struct FitFrame {
  int round = 0;        // rounds done, over every stage (1-based)
  int stage = 0;        // the round's stage (0-based)
  int max_rounds = 0;   // stages x rounds per stage (stages usually settle sooner)
  double residual = 0;  // mean source -> target distance at the round's start / the target's diagonal
  bool running = false; // more rounds follow
  // The last frame's: the mean distance after the pre-alignment and of the final shape, the final shape's
  // 90th percentile (/ diagonal), and how the fit ended.
  double initial_mean = 0, final_mean = 0, final_p90 = 0;
  bool cancelled = false; // stopped by POST /api/cancel or a newer generation, at that round's shape
  bool committed = false; // the shape became the method's positions (the session had not moved on)
};

struct SessionFrame {
  std::uint64_t sequence = 0;   // set by FrameBoard::publish: 1, 2, ... in the order of publication
  std::uint64_t generation = 0; // the session's generation: targets, constraints or mesh it belongs to
  ArapMethod method = ArapMethod::Iarap;
  bool refined = false;         // made by the background refinement (false: a solve's answer)
  int iterations = 0;           // iterations behind it since the answer of its generation
  double energy = 0;            // E(U) of the positions
  double relative_decrease = 0; // (E_prev - E) / E_prev of its last iteration, what the tolerance stops
  double tolerance = 0;         // the refinement's stopping tolerance on relative_decrease
  bool refining = false;        // the refinement continues: more frames of this generation will follow
  bool converged = false;       // the tolerance was reached
  std::string error;            // the refinement failed (the solver's message); positions stay the last
  std::vector<float> positions; // #V x 3 row-major
  std::optional<FitFrame> fit;  // a fit's frame (refined false; energy the round's E_ARAP + P)
};

class FrameBoard {
public:
  // Numbers the frame, keeps it as the latest and wakes the waiters; returns its sequence.
  std::uint64_t publish(SessionFrame frame);
  // The latest frame once its sequence is above after, waiting at most timeout; nullptr when none came.
  std::shared_ptr<const SessionFrame> wait_newer(std::uint64_t after,
                                                 std::chrono::milliseconds timeout) const;
  // The sequence of the latest frame (0 before any): a client waiting for the frames of a job it starts
  // asks for those after it.
  std::uint64_t latest_sequence() const;
  // Wakes every waiter with nothing (server shutdown); later waits return at once.
  void close();

private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const SessionFrame> latest_;
  std::uint64_t next_sequence_ = 1;
  bool closed_ = false;
};

} // namespace iarap::serve
