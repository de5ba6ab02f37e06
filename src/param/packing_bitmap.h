// The raster packing's occupancy bitmap (chart_packing.h) and its search for a chart's lowest free place.
//
// The search asks, for each height y, at which x a chart's cells meet no occupied cell. Testing the x one
// at a time (jumping past each conflict) cost the ogre's 588 charts 784K x-scans that found nothing
// (docs/param.md). Here every x of a row is tested at once, 64 to a word: for a run of L cells of the chart
// at offset b, the x where it fits are the zero bits of "some cell in [x + b, x + b + L) occupied", which
// two shifts of a precomputed level give (level k: some cell in [p, p + 2^k) occupied, so that any L in
// [2^k, 2^(k+1)) is the union of two windows of 2^k). The candidates of a height are the AND over the
// chart's runs; most heights are empty after a few rows.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

namespace iarap::param_detail {

// A chart's cells on the packing bitmap: per row, runs [begin, end) of occupied cells.
struct CellMask {
  int width = 0, height = 0;
  std::vector<std::vector<std::pair<int, int>>> runs;
};

// A square of size x size cells, all free at first.
class CellBitmap {
public:
  explicit CellBitmap(int size);
  int size() const { return size_; }
  int words() const { return words_; }
  void clear(); // every cell free again

  bool occupied(int y, int x) const;
  // Occupies cells [begin, end) of row y.
  void set(int y, int begin, int end);
  // The longest run of free cells in row y.
  int longest_free(int y) const { return longest_free_[static_cast<std::size_t>(y)]; }
  // Clears bit x of candidates (words() words) unless cells [x + offset, x + offset + length) of row y
  // are all free (cells past the row count as occupied); returns whether any candidate is left.
  bool keep_fitting(int y, int offset, int length, std::uint64_t* candidates) const;

private:
  const std::uint64_t* level(int y, int k) const {
    return &blocked_[(static_cast<std::size_t>(y) * levels_ + static_cast<std::size_t>(k)) * words_];
  }
  std::uint64_t* level(int y, int k) {
    return &blocked_[(static_cast<std::size_t>(y) * levels_ + static_cast<std::size_t>(k)) * words_];
  }
  void refresh(int y); // the levels above 0 and the longest free run, after level 0 changed

  int size_, words_, levels_;
  // Per row and level k, bit p: some cell of [p, p + 2^k) occupied or past the row.
  std::vector<std::uint64_t> blocked_;
  std::vector<int> longest_free_;
};

// The lowest (then leftmost) place where the mask meets no occupied cell with its top row at most max_top
// (y + height <= max_top) and x + width <= size: (x, y), or (-1, -1).
Eigen::Vector2i lowest_place(const CellBitmap& bitmap, const CellMask& mask, int max_top);

} // namespace iarap::param_detail
