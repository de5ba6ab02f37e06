// Wall-clock timing in milliseconds: the one clock every timing field of the library and the tool reads.
#pragma once
#include <chrono>

namespace iarap {

using Clock = std::chrono::steady_clock;

// Milliseconds from start to now.
inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Adds the time from its construction to its destruction to `total` (milliseconds): a block's cost
// accumulated into a report field without clock arithmetic at the call site.
class ScopedTimer {
public:
  explicit ScopedTimer(double& total) : total_(total), start_(Clock::now()) {}
  ~ScopedTimer() { total_ += ms_since(start_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
  double& total_;
  Clock::time_point start_;
};

// Runs f(), adds its duration to total (milliseconds) and returns what f returns.
template <class F> decltype(auto) timed(double& total, F&& f) {
  const ScopedTimer timer(total);
  return f();
}

} // namespace iarap
