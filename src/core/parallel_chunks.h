// Internal: a parallel loop that threads busy elsewhere can join when they are done.
#pragma once
#include "iarap/core/threads.h"

#include <omp.h>

#include <algorithm>

namespace iarap::detail {

// Upper bound (exclusive) of the `worker` that parallel_chunks passes to its body.
inline int chunk_workers() { return std::max(omp_get_max_threads(), omp_in_parallel() ? omp_get_num_threads() : 1); }

// Calls body(begin, end, worker) on consecutive chunks [begin, end) of [0, n), at most `grain` long, in
// parallel; `worker` (< chunk_workers()) is the calling thread, for per-thread buffers. body must not throw.
//
// Inside a team of several threads (arap_precompute's region, where the other thread runs CHOLMOD's
// analysis) the chunks are OpenMP tasks: a thread that has finished its own part waits at the region's end,
// and waiting threads run pending tasks, so it joins this loop at whatever point it arrives. Elsewhere, a
// dynamic loop over loop_thread_count() threads.
template <class Body>
void parallel_chunks(int n, int grain, const Body& body) {
  const int chunks = (n + grain - 1) / grain;
  if (omp_in_parallel() && omp_get_num_threads() > 1) {
#pragma omp taskloop grainsize(1)
    for (int c = 0; c < chunks; ++c) body(c * grain, std::min(n, (c + 1) * grain), omp_get_thread_num());
  } else {
#pragma omp parallel for num_threads(loop_thread_count()) schedule(dynamic, 1)
    for (int c = 0; c < chunks; ++c) body(c * grain, std::min(n, (c + 1) * grain), omp_get_thread_num());
  }
}

} // namespace iarap::detail
