// Thread count used by the parallel loops of the library (OpenMP underneath).
#pragma once

namespace iarap {

// Sets the number of threads for later parallel work; n <= 0 means all hardware threads.
void set_thread_count(int n);

// The number of threads parallel loops will use.
int thread_count();

// Below this many vertices a team of threads costs more than it saves: waking it, and on a busy machine
// waiting at each loop's end for a thread the scheduler put behind other work. Measured with `deform`
// (iarap, 5 iterations) on a loaded 2-core machine, median of 3 paired rounds, time with 2 threads over 1:
// decimated-knight (502 vertices) 3.77, bunny (3.5K) 2.02, horse (5K) 1.56, armadillo_30K (15K) 1.02,
// beetle (20K) 1.02 (the issue: a 382-vertex sphere 1.37 s against 0.12 s).
constexpr int serial_vertex_threshold = 10000;

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
