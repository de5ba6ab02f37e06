// Internal: two pieces of the preprocess at the same time on two threads, a serial CHOLMOD call beside the
// work that does not need its result (arap_precompute).
#pragma once
#include <functional>

namespace iarap::detail {

// Where run_beside runs side() while main() runs.
enum class Beside {
  // side() on the second thread of an OpenMP region of two (the pool's thread, already there and warm),
  // main() on the caller's. For the symbolic analysis beside the element build: a std::thread for it
  // started 1-2 ms after it was created and the build around it took 3-4 ms longer (beetle, original ARAP,
  // 2 threads: precompute 58-60 against 54-55 ms).
  SecondTeamThread,
  // side() on the caller's thread outside any OpenMP region, main() on a std::thread. For the numeric
  // factorization: CHOLMOD's supernodal factorization enters about 16,500 serialized OpenMP regions on
  // beetle, and inside an enclosing team libgomp allocates, initializes and frees a team for each one where
  // at the top level it reuses one (16,500 empty regions: 25 against 49 ms). On one thread of a region of
  // two it took 54-56 ms against 35-38 ms here (iARAP precompute, 2 threads: 70 -> 53 ms). On the caller's
  // thread the factor is allocated from the caller's heap arena, which keeps the pages of what it freed
  // (every other thread gets an arena of its own: beetle, iARAP, 6600 against 5300 page faults).
  CallerOutsideOpenMP,
};

// Runs side() and main() at the same time when two threads are allowed, else one after the other; the
// first exception of either is rethrown after both have ended (main()'s first). side() is a serial CHOLMOD
// call (the symbolic analysis, the numeric factorization), main() what the precompute can do meanwhile.
// side() is allowed one thread (the setting of the thread that runs it): SparseCholesky then keeps CHOLMOD's
// own teams from crowding the cores main() is using (beetle's factorization beside the element finish: 29
// ms, 128 ms with CHOLMOD's teams). main()'s loops run on the cores side() leaves (CoreReservation;
// threads.h says why): one on a 2-core machine.
void run_beside(const std::function<void()>& side, const std::function<void()>& main, Beside where);

} // namespace iarap::detail
