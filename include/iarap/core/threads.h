// Thread count used by the parallel loops of the library (OpenMP underneath).
#pragma once

namespace iarap {

// Sets the number of threads for later parallel work; n <= 0 means all hardware threads.
void set_thread_count(int n);

// The number of threads parallel loops will use.
int thread_count();

// Below this many vertices the whole deformation takes milliseconds, and a team of threads costs more
// than it saves: waking it, and on a busy machine waiting at each loop's end for a thread the scheduler
// put behind other work (measured on a loaded 2-core machine: a 382-vertex sphere 1.37 s with all threads
// against 0.12 s with one).
constexpr int serial_vertex_threshold = 5000;

// The thread count an automatic choice (--threads 0) should use for a mesh of `vertices` vertices: 1
// below serial_vertex_threshold, else every hardware thread.
int automatic_thread_count(int vertices);

// The threads a parallel loop of the preprocess should use now: thread_count() less the cores that
// reservations hold, at least 1. While another thread of ours keeps a core busy (arap_precompute's symbolic
// analysis beside the intrinsic triangulation), a loop split over every core waits at its end for the
// thread that analysis displaced: a scheduler time slice, often longer than the loop. Measured on a 2-core
// machine, the intrinsic preprocess then ran no faster than on one thread.
int loop_thread_count();

// Holds one core for a helper thread from construction to destruction (movable, so that the helper can
// own it): loop_thread_count() is one lower meanwhile. Make it before starting the helper.
class CoreReservation {
public:
  CoreReservation();
  ~CoreReservation();
  CoreReservation(CoreReservation&& other) noexcept;
  CoreReservation& operator=(CoreReservation&&) = delete;
  CoreReservation(const CoreReservation&) = delete;
  CoreReservation& operator=(const CoreReservation&) = delete;

private:
  bool held_ = true;
};

} // namespace iarap
