// The viewer's fit: the session's rest mesh registered to the loaded target (register.h: non-rigid ICP with
// the ARAP energy) on a thread of its own, one fit at a time, without the session mutex (a fit takes
// seconds; the page stays usable), publishing a frame after every round (round, residual, positions) and
// one at the end. It stops at the next round boundary on cancel() or once the session moved to another
// generation (a solve, a new constraint set or mesh); the shape it reached becomes the method's positions
// unless the session moved on.
#pragma once
#include "session.h"

#include "iarap/registration/register.h"

#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>

namespace iarap::serve {

class SharedSession;

struct FitRequest {
  ArapMethod method = ArapMethod::Iarap;
  RegistrationOptions options; // stages, rounds_per_stage, prealignment (the rest: the library's defaults)
};

// What POST /api/fit answers: the fit's generation, and the frame sequence its frames come after.
struct FitStarted {
  std::uint64_t generation = 0;
  std::uint64_t after = 0;
};

class FitRunner {
public:
  FitRunner() = default;
  ~FitRunner(); // stop()
  FitRunner(const FitRunner&) = delete;
  FitRunner& operator=(const FitRunner&) = delete;

  // Starts a fit (Session::begin_fit under the session mutex). Throws SessionConflict while a fit runs,
  // and what begin_fit throws (no mesh or target).
  FitStarted start(SharedSession& shared, const FitRequest& request);
  // Asks the running fit to stop at its next round boundary; false when none runs.
  bool cancel();
  bool running() const { return running_.load(); }
  // cancel() and waits for the thread (server shutdown).
  void stop();

private:
  void run(SharedSession& shared, FitStart start, FitRequest request);

  std::mutex mutex_; // start and stop
  std::thread thread_;
  std::atomic<bool> running_{false}, cancel_{false};
};

} // namespace iarap::serve
