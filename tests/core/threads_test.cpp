#include "iarap/core/threads.h"

#include <gtest/gtest.h>

TEST(Threads, SetAndReadBack) {
  iarap::set_thread_count(1);
  EXPECT_EQ(iarap::thread_count(), 1);
  iarap::set_thread_count(0);
  EXPECT_GE(iarap::thread_count(), 1);
}
