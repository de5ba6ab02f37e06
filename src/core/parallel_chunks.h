// Internal: a parallel loop over chunks of uneven cost, with a per-thread buffer index.
#pragma once
#include "iarap/core/threads.h"

#include <omp.h>

#include <algorithm>

namespace iarap::detail {

// Upper bound (exclusive) of the `worker` that parallel_chunks passes to its body.
inline int chunk_workers() {
  return std::max(omp_get_max_threads(), omp_in_parallel() ? omp_get_num_threads() : 1);
}

// Calls body(begin, end, worker) on consecutive chunks [begin, end) of [0, n), at most `grain` long, in
// parallel over loop_thread_count() threads (dynamic: chunks of uneven cost); `worker` (< chunk_workers())
// is the calling thread, for per-thread buffers. body must not throw.
template <class Body> void parallel_chunks(int n, int grain, const Body& body) {
  const int chunks = (n + grain - 1) / grain;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(dynamic, 1)
  for (int c = 0; c < chunks; ++c) body(c * grain, std::min(n, (c + 1) * grain), omp_get_thread_num());
}

} // namespace iarap::detail
