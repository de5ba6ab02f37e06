#include "iarap/core/threads.h"

#include <omp.h>

#include <algorithm>
#include <atomic>

namespace iarap {

void set_thread_count(int n) {
  omp_set_num_threads(n > 0 ? n : omp_get_num_procs());
}

int thread_count() {
  return omp_get_max_threads();
}

int automatic_thread_count(int vertices) {
  return vertices < serial_vertex_threshold ? 1 : omp_get_num_procs();
}

namespace {
std::atomic<int> reserved_cores{0};
} // namespace

int loop_thread_count() {
  return std::max(1, omp_get_max_threads() - reserved_cores.load(std::memory_order_relaxed));
}

CoreReservation::CoreReservation() {
  reserved_cores.fetch_add(1, std::memory_order_relaxed);
}

CoreReservation::~CoreReservation() {
  if (held_) reserved_cores.fetch_sub(1, std::memory_order_relaxed);
}

CoreReservation::CoreReservation(CoreReservation&& other) noexcept : held_(other.held_) {
  other.held_ = false;
}

} // namespace iarap
