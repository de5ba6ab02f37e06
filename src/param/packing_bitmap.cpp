#include "packing_bitmap.h"

#include <algorithm>
#include <numeric>

namespace iarap::param_detail {

namespace {

constexpr std::uint64_t all_ones = ~std::uint64_t{0};

// Word i of a row read `shift` bits further on (bit p of the result is bit p + shift of the row); bits
// past the row's words read as set (occupied).
std::uint64_t shifted_word(const std::uint64_t* row, int words, int i, int shift) {
  const int q = i + shift / 64, r = shift % 64;
  const std::uint64_t low = q < words ? row[q] : all_ones;
  if (r == 0) return low;
  const std::uint64_t high = q + 1 < words ? row[q + 1] : all_ones;
  return (low >> r) | (high << (64 - r));
}

} // namespace

CellBitmap::CellBitmap(int size)
    : size_(size), words_((size + 63) / 64), levels_(1), longest_free_(static_cast<std::size_t>(size), size) {
  while ((2 << (levels_ - 1)) <= size_) ++levels_; // 2^(levels - 1) <= size < 2^levels
  blocked_.resize(static_cast<std::size_t>(size_) * static_cast<std::size_t>(levels_) *
                  static_cast<std::size_t>(words_));
  clear();
}

void CellBitmap::clear() {
  for (int y = 0; y < size_; ++y) {
    std::uint64_t* row = level(y, 0);
    std::fill(row, row + words_, 0);
    if (size_ % 64 != 0) row[words_ - 1] = all_ones << (size_ % 64); // past the row: occupied
    refresh(y);
  }
}

bool CellBitmap::occupied(int y, int x) const {
  return (level(y, 0)[x / 64] >> (x % 64)) & 1;
}

void CellBitmap::set(int y, int begin, int end) {
  std::uint64_t* row = level(y, 0);
  for (int x = begin; x < end; ++x) row[x / 64] |= std::uint64_t{1} << (x % 64);
  refresh(y);
}

void CellBitmap::refresh(int y) {
  for (int k = 1; k < levels_; ++k) {
    const std::uint64_t* below = level(y, k - 1);
    std::uint64_t* row = level(y, k);
    for (int i = 0; i < words_; ++i) row[i] = below[i] | shifted_word(below, words_, i, 1 << (k - 1));
  }
  // The longest free run: from each first free cell to the next occupied one (the padding bits stop it).
  const std::uint64_t* row = level(y, 0);
  int longest = 0;
  for (int x = 0; x < size_;) {
    const std::uint64_t free_bits = ~row[x / 64] >> (x % 64);
    if (free_bits == 0) {
      x = (x / 64 + 1) * 64;
      continue;
    }
    const int begin = x + __builtin_ctzll(free_bits);
    int end = begin;
    while (end < size_) {
      const std::uint64_t set_bits = row[end / 64] >> (end % 64);
      if (set_bits != 0) {
        end += __builtin_ctzll(set_bits);
        break;
      }
      end = (end / 64 + 1) * 64;
    }
    end = std::min(end, size_);
    longest = std::max(longest, end - begin);
    x = end;
  }
  longest_free_[static_cast<std::size_t>(y)] = longest;
}

bool CellBitmap::keep_fitting(int y, int offset, int length, std::uint64_t* candidates) const {
  if (length > size_) {
    std::fill(candidates, candidates + words_, 0);
    return false;
  }
  // [x + offset, x + offset + length) is the union of the level-k windows at x + offset and at
  // x + offset + length - 2^k, 2^k <= length < 2^(k+1).
  const int k = 63 - __builtin_clzll(static_cast<unsigned long long>(length));
  const int second = offset + length - (1 << k);
  const std::uint64_t* row = level(y, k);
  std::uint64_t left = 0;
  for (int i = 0; i < words_; ++i) {
    candidates[i] &= ~(shifted_word(row, words_, i, offset) | shifted_word(row, words_, i, second));
    left |= candidates[i];
  }
  return left != 0;
}

Eigen::Vector2i lowest_place(const CellBitmap& bitmap, const CellMask& mask, int max_top) {
  const int n = bitmap.size();
  if (mask.width > n || mask.height > n) return Eigen::Vector2i(-1, -1);
  std::vector<int> widest(static_cast<std::size_t>(mask.height), 0);
  for (int r = 0; r < mask.height; ++r)
    for (const auto& [begin, end] : mask.runs[static_cast<std::size_t>(r)])
      widest[static_cast<std::size_t>(r)] = std::max(widest[static_cast<std::size_t>(r)], end - begin);
  // Rows are tested widest first (the likeliest to fail).
  std::vector<int> rows(static_cast<std::size_t>(mask.height));
  std::iota(rows.begin(), rows.end(), 0);
  std::stable_sort(rows.begin(), rows.end(), [&widest](int a, int b) {
    return widest[static_cast<std::size_t>(a)] > widest[static_cast<std::size_t>(b)];
  });
  // Every x with x + width <= n, one bit each.
  const int words = bitmap.words();
  std::vector<std::uint64_t> every(static_cast<std::size_t>(words), 0), candidates(every.size());
  for (int x = 0; x + mask.width <= n; ++x)
    every[static_cast<std::size_t>(x / 64)] |= std::uint64_t{1} << (x % 64);
  for (int y = 0; y + mask.height <= std::min(n, max_top);) {
    // A mask row wider than its bitmap row's longest free run rules out y at once. Every later y' that
    // puts a mask row at least as wide on that bitmap row fails too: the search jumps to the first y'
    // that puts a narrower one there, or past it.
    int blocked = -1;
    for (std::size_t i = 0; i < rows.size() && blocked < 0; ++i)
      if (bitmap.longest_free(y + rows[i]) < widest[static_cast<std::size_t>(rows[i])]) blocked = rows[i];
    if (blocked >= 0) {
      const int free_run = bitmap.longest_free(y + blocked);
      int shift = 1;
      while (shift <= blocked && widest[static_cast<std::size_t>(blocked - shift)] > free_run) ++shift;
      y += shift;
      continue;
    }
    candidates = every;
    bool left = true;
    for (std::size_t i = 0; i < rows.size() && left; ++i)
      for (const auto& [begin, end] : mask.runs[static_cast<std::size_t>(rows[i])])
        if (!(left = bitmap.keep_fitting(y + rows[i], begin, end - begin, candidates.data()))) break;
    if (left)
      for (int i = 0; i < words; ++i)
        if (candidates[static_cast<std::size_t>(i)] != 0)
          return Eigen::Vector2i(64 * i + __builtin_ctzll(candidates[static_cast<std::size_t>(i)]), y);
    ++y;
  }
  return Eigen::Vector2i(-1, -1);
}

} // namespace iarap::param_detail
