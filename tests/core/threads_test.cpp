#include "iarap/core/threads.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <utility>

TEST(Threads, SetAndReadBack) {
  iarap::set_thread_count(1);
  EXPECT_EQ(iarap::thread_count(), 1);
  iarap::set_thread_count(0);
  EXPECT_GE(iarap::thread_count(), 1);
}

TEST(Threads, CoreReservationLowersLoopThreadsWhileHeld) {
  iarap::set_thread_count(3);
  EXPECT_EQ(iarap::loop_thread_count(), 3);
  {
    iarap::CoreReservation first;
    EXPECT_EQ(iarap::loop_thread_count(), 2);
    iarap::CoreReservation moved = std::move(first); // the moved-from one no longer holds a core
    EXPECT_EQ(iarap::loop_thread_count(), 2);
    {
      iarap::CoreReservation second, third; // never below one thread
      EXPECT_EQ(iarap::loop_thread_count(), 1);
    }
    EXPECT_EQ(iarap::loop_thread_count(), 2);
  }
  EXPECT_EQ(iarap::loop_thread_count(), 3);
  iarap::set_thread_count(0);
}

// Small meshes run on one thread by default (issue 20: a 382-vertex sphere took 1.37 s on all threads of a
// busy 2-core machine, 0.12 s on one); large ones on every hardware thread.
TEST(Threads, AutomaticCountIsSerialBelowTheThreshold) {
  EXPECT_EQ(iarap::automatic_thread_count(382), 1);
  EXPECT_EQ(iarap::automatic_thread_count(iarap::serial_vertex_threshold - 1), 1);
  EXPECT_GE(iarap::automatic_thread_count(iarap::serial_vertex_threshold), 1);
  EXPECT_EQ(iarap::automatic_thread_count(1000000), omp_get_num_procs());
}
