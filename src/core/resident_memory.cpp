#include "iarap/core/resident_memory.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace iarap {

std::size_t peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024; // kilobytes on Linux
}

std::size_t current_resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

void release_free_heap() {
  malloc_trim(0);
}

void release_free_heap(std::ptrdiff_t vertices) {
  // From this many vertices the freed transients of a precompute's phase are hundreds of megabytes (issue
  // 44), and their page faults a small part of a precompute of seconds.
  constexpr std::ptrdiff_t kReleaseHeapVertices = 100000;
  if (vertices >= kReleaseHeapVertices) release_free_heap();
}

void trace_resident(const char* phase) {
  static const bool enabled = std::getenv("IARAP_MEMORY_TRACE") != nullptr;
  if (!enabled) return;
  const struct mallinfo2 heap = mallinfo2();
  // Seconds since the first trace of the process: where a precompute's phases end on both threads.
  static const auto first = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - first).count();
  std::fprintf(stderr, "memory: %s at %.2f s resident %.1f MB peak %.1f MB (malloc in use %.1f MB)\n", phase,
               seconds, current_resident_bytes() / 1e6, peak_resident_bytes() / 1e6,
               static_cast<double>(heap.uordblks + heap.hblkhd) / 1e6);
}

} // namespace iarap
