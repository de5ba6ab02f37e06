#include "run_beside.h"

#include "iarap/core/threads.h"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <optional>
#include <system_error>
#include <thread>

namespace iarap::detail {

void run_beside(const std::function<void()>& side, const std::function<void()>& main, Beside where) {
  if (omp_get_max_threads() <= 1 || omp_in_parallel()) {
    side();
    main();
    return;
  }
  const int threads = omp_get_max_threads();
  std::exception_ptr side_error, main_error;
  // side()'s core, given back to main()'s loops as soon as side() ends: with an optimized BLAS the
  // numeric factorization ends well before the intrinsic build beside it (armadillo subdivided twice,
  // 0.7 of 6 s), whose later loops (tracing, elements, the streamed layout) then run on every core.
  std::optional<CoreReservation> core;
  auto run_side = [&] {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    try {
      side();
    } catch (...) {
      side_error = std::current_exception();
    }
    omp_set_num_threads(saved);
    core.reset();
  };
  auto run_main = [&] {
    try {
      main();
    } catch (...) {
      main_error = std::current_exception();
    }
  };
  bool beside = false; // false: the runtime gave one thread, or no thread could be made
  {
    core.emplace();
    if (where == Beside::SecondTeamThread) {
      // main()'s loops may open nested teams on machines with more cores: allowed for the region's duration.
      const int active_levels = omp_get_max_active_levels();
      omp_set_max_active_levels(std::max(active_levels, 2));
#pragma omp parallel num_threads(2)
      {
        if (omp_get_num_threads() == 2) {
          if (omp_get_thread_num() == 0) {
            beside = true;
            run_main();
          } else {
            run_side();
          }
        }
      }
      omp_set_max_active_levels(active_levels);
    } else {
      std::thread helper;
      try {
        helper = std::thread([&] {
          // A new thread starts from OpenMP's initial settings, not the caller's.
          omp_set_num_threads(threads);
          run_main();
        });
        beside = true;
      } catch (const std::system_error&) { // no thread to be had: one after the other, below
      }
      if (beside) {
        run_side();
        helper.join();
      }
    }
    core.reset();
  }
  if (!beside) {
    side();
    main();
    return;
  }
  if (main_error) std::rethrow_exception(main_error);
  if (side_error) std::rethrow_exception(side_error);
}

} // namespace iarap::detail
