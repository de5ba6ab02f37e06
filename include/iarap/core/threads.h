// Thread count used by the parallel loops of the library (OpenMP underneath).
#pragma once

namespace iarap {

// Sets the number of threads for later parallel work; n <= 0 means all hardware threads.
void set_thread_count(int n);

// The number of threads parallel loops will use.
int thread_count();

} // namespace iarap
