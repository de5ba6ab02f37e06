#include "iarap/core/threads.h"

#include <gtest/gtest.h>

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
