#include "solver/metis_ordering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace {

// The 5-point Laplacian pattern of a side x side grid (values: the graph only matters).
Eigen::SparseMatrix<double> grid_pattern(int side) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [side](int x, int y) { return y * side + x; };
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      t.emplace_back(id(x, y), id(x, y), 4.0);
      if (x + 1 < side) {
        t.emplace_back(id(x + 1, y), id(x, y), -1.0);
        t.emplace_back(id(x, y), id(x + 1, y), -1.0);
      }
      if (y + 1 < side) {
        t.emplace_back(id(x, y + 1), id(x, y), -1.0);
        t.emplace_back(id(x, y), id(x, y + 1), -1.0);
      }
    }
  Eigen::SparseMatrix<double> A(side * side, side * side);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// The largest connected part of the grid once the vertices `removed` marks are taken out.
int largest_part(int side, const std::vector<bool>& removed) {
  std::vector<bool> seen(removed);
  int largest = 0;
  for (int start = 0; start < side * side; ++start) {
    if (seen[start]) continue;
    int size = 0;
    std::vector<int> stack{start};
    seen[start] = true;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      ++size;
      const int x = v % side, y = v / side;
      for (const auto& [nx, ny] : {std::pair{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}}) {
        if (nx < 0 || ny < 0 || nx >= side || ny >= side || seen[ny * side + nx]) continue;
        seen[ny * side + nx] = true;
        stack.push_back(ny * side + nx);
      }
    }
    largest = std::max(largest, size);
  }
  return largest;
}

} // namespace

// METIS answers with a permutation; the same one from the full pattern and from its lower triangle alone.
TEST(MetisOrdering, IsAPermutationOfTheRows) {
  const Eigen::SparseMatrix<double> A = grid_pattern(40);
  const std::vector<int> perm = iarap::detail::metis_nested_dissection(A);
  ASSERT_EQ(perm.size(), static_cast<size_t>(A.rows()));
  std::vector<int> sorted(perm);
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < A.rows(); ++i) ASSERT_EQ(sorted[i], i);
  const Eigen::SparseMatrix<double> lower = A.triangularView<Eigen::Lower>();
  EXPECT_EQ(iarap::detail::metis_nested_dissection(lower), perm);
}

// A nested dissection eliminates a small separator last: on a 60 x 60 grid the top separator is about one
// grid line, so taking out the last 1.5 x 60 rows (it and the start of the separator below it, which METIS
// numbers just before) cuts the grid in two, the larger part at most 0.6 of it (METIS allows an imbalance
// of 1.2 at each cut). An ordering without separators (the natural one: the last 1.5 grid rows) leaves one
// part of 3510 vertices.
TEST(MetisOrdering, EliminatesSeparatorsLast) {
  const int side = 60, n = side * side, last = 3 * side / 2;
  const std::vector<int> perm = iarap::detail::metis_nested_dissection(grid_pattern(side));
  ASSERT_EQ(perm.size(), static_cast<size_t>(n));
  std::vector<bool> removed(n, false);
  for (int k = n - last; k < n; ++k) removed[perm[k]] = true;
  EXPECT_LE(largest_part(side, removed), 0.6 * n);
  std::vector<bool> natural(n, false);
  for (int k = n - last; k < n; ++k) natural[k] = true;
  EXPECT_GT(largest_part(side, natural), 0.9 * n);
}

// An empty or non-square pattern has nothing to order.
TEST(MetisOrdering, EmptyForNothingToOrder) {
  EXPECT_TRUE(iarap::detail::metis_nested_dissection(Eigen::SparseMatrix<double>(0, 0)).empty());
  EXPECT_TRUE(iarap::detail::metis_nested_dissection(Eigen::SparseMatrix<double>(3, 2)).empty());
}
