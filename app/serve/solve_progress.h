// Progress of the solve in flight, readable and cancellable without the session mutex the solve holds:
// GET /api/progress polls it, POST /api/cancel sets cancel_requested, which the solve checks after every
// iteration (ArapSolveOptions::on_iteration).
#pragma once
#include <atomic>

namespace iarap::serve {

struct SolveProgress {
  std::atomic<bool> running{false};
  std::atomic<bool> cancel_requested{false};
  std::atomic<int> method{0};     // ArapMethod as an integer
  std::atomic<int> iteration{0};  // iterations done so far
  std::atomic<int> iterations{0}; // the request's limit
  std::atomic<double> energy{0};  // after the last finished iteration
};

} // namespace iarap::serve
