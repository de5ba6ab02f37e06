// The packing bitmap's word-parallel search against the exhaustive one: on random bitmaps and random chart
// masks, the lowest (then leftmost) place must be the first (y, x) whose every mask cell is free, so that
// neither the rows skipped by their longest free run nor the x ruled out 64 at a time lose a place.
#include "param/packing_bitmap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace iarap::param_detail {
namespace {

bool fits(const CellBitmap& bitmap, const CellMask& mask, int x, int y) {
  for (int r = 0; r < mask.height; ++r)
    for (const auto& [begin, end] : mask.runs[static_cast<std::size_t>(r)])
      for (int c = begin; c < end; ++c)
        if (bitmap.occupied(y + r, x + c)) return false;
  return true;
}

Eigen::Vector2i exhaustive_place(const CellBitmap& bitmap, const CellMask& mask, int max_top) {
  const int n = bitmap.size();
  for (int y = 0; y + mask.height <= std::min(n, max_top); ++y)
    for (int x = 0; x + mask.width <= n; ++x)
      if (fits(bitmap, mask, x, y)) return Eigen::Vector2i(x, y);
  return Eigen::Vector2i(-1, -1);
}

// A random blob: per row one or two runs inside the width, some rows wider than others.
CellMask random_mask(std::mt19937& random, int max_side) {
  std::uniform_int_distribution<int> side(1, max_side);
  CellMask mask;
  mask.width = side(random);
  mask.height = side(random);
  mask.runs.resize(static_cast<std::size_t>(mask.height));
  for (auto& runs : mask.runs) {
    std::uniform_int_distribution<int> at(0, mask.width - 1);
    int a = at(random), b = at(random);
    if (a > b) std::swap(a, b);
    if (b - a >= 3 && random() % 3 == 0) { // two runs with a gap
      const int cut = a + 1 + static_cast<int>(random() % static_cast<unsigned>(b - a - 2));
      runs.push_back({a, cut});
      runs.push_back({cut + 1, b + 1});
    } else {
      runs.push_back({a, b + 1});
    }
  }
  return mask;
}

void occupy_randomly(std::mt19937& random, CellBitmap& bitmap, int blocks, int max_side) {
  const int n = bitmap.size();
  std::uniform_int_distribution<int> at(0, n - 1), side(1, max_side);
  for (int i = 0; i < blocks; ++i) {
    const int x = at(random), y = at(random), w = side(random), h = side(random);
    for (int r = y; r < std::min(n, y + h); ++r) bitmap.set(r, x, std::min(n, x + w));
  }
}

TEST(PackingBitmap, LongestFreeRunMatchesTheCells) {
  std::mt19937 random(7);
  for (int size : {16, 64, 100, 130, 512}) {
    CellBitmap bitmap(size);
    for (int y = 0; y < size; ++y) EXPECT_EQ(bitmap.longest_free(y), size);
    occupy_randomly(random, bitmap, size / 2, std::max(2, size / 8));
    for (int y = 0; y < size; ++y) {
      int longest = 0, run = 0;
      for (int x = 0; x < size; ++x) {
        run = bitmap.occupied(y, x) ? 0 : run + 1;
        longest = std::max(longest, run);
      }
      EXPECT_EQ(bitmap.longest_free(y), longest) << "size " << size << " row " << y;
    }
    bitmap.clear();
    for (int y = 0; y < size; ++y) EXPECT_EQ(bitmap.longest_free(y), size);
  }
}

TEST(PackingBitmap, LowestPlaceEqualsTheExhaustiveSearch) {
  std::mt19937 random(11);
  int placed = 0, none = 0;
  for (int size : {16, 64, 100, 130, 200}) {
    for (int trial = 0; trial < 40; ++trial) {
      CellBitmap bitmap(size);
      // From nearly empty to crowded, so that places are found low, high and not at all.
      occupy_randomly(random, bitmap, trial * size / 20, std::max(2, size / 6));
      for (int m = 0; m < 5; ++m) {
        const CellMask mask = random_mask(random, std::max(1, size / 4));
        const int max_top = m == 4 ? size / 2 : size;
        const Eigen::Vector2i expected = exhaustive_place(bitmap, mask, max_top);
        EXPECT_EQ(lowest_place(bitmap, mask, max_top), expected)
            << "size " << size << " trial " << trial << " mask " << m;
        (expected.x() >= 0 ? placed : none) += 1;
      }
    }
  }
  // Both outcomes occur often enough for the comparison to mean something.
  EXPECT_GT(placed, 100);
  EXPECT_GT(none, 100);
}

TEST(PackingBitmap, PlacesTouchTheRowsEnd) {
  // A row free only in its last cells: a run of exactly that length fits there, one longer does not.
  for (int size : {64, 100, 128}) {
    CellBitmap bitmap(size);
    bitmap.set(0, 0, size - 5);
    CellMask mask;
    mask.width = 5;
    mask.height = 1;
    mask.runs = {{{0, 5}}};
    EXPECT_EQ(lowest_place(bitmap, mask, 1), Eigen::Vector2i(size - 5, 0));
    mask.width = 6;
    mask.runs = {{{0, 6}}};
    EXPECT_EQ(lowest_place(bitmap, mask, 1), Eigen::Vector2i(-1, -1));
    EXPECT_EQ(lowest_place(bitmap, mask, 2), Eigen::Vector2i(0, 1));
  }
}

} // namespace
} // namespace iarap::param_detail
