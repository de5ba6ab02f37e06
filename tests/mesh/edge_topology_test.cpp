#include "iarap/mesh/edge_topology.h"

#include "iarap/io/read_mesh.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>
#include <vector>

namespace {

using namespace iarap;

// Reference: sort every face corner by (smaller, larger vertex of its opposite edge, face, corner).
void expect_matches_sorted_reference(const Eigen::MatrixXi& F, int nv) {
  std::vector<std::tuple<int, int, int, int>> corners;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      corners.emplace_back(std::min(a, b), std::max(a, b), f, k);
    }
  std::sort(corners.begin(), corners.end());
  const EdgeTopology t = edge_topology(F, nv);
  int e = -1;
  for (size_t i = 0; i < corners.size(); ++i) {
    const auto [lo, hi, f, k] = corners[i];
    if (i == 0 || std::get<0>(corners[i - 1]) != lo || std::get<1>(corners[i - 1]) != hi) {
      ++e;
      ASSERT_LT(e, t.E.rows());
      EXPECT_EQ(t.E(e, 0), lo);
      EXPECT_EQ(t.E(e, 1), hi);
    }
    EXPECT_EQ(t.FE(f, k), e);
    int slot = 0;
    for (size_t j = i; j > 0 && std::get<0>(corners[j - 1]) == lo && std::get<1>(corners[j - 1]) == hi; --j)
      ++slot;
    if (slot < 2) {
      EXPECT_EQ(t.EF(e, slot), f);
      EXPECT_EQ(t.EK(e, slot), k);
    }
  }
  EXPECT_EQ(e + 1, t.E.rows());
}

TEST(EdgeTopology, MatchesTheSortedReferenceOnTheBunny) {
  const MeshData m = read_mesh(test::data_path("bunny.off"));
  expect_matches_sorted_reference(m.F, static_cast<int>(m.V.rows()));
}

// Three faces on edge (0, 1): counted, the first two (by face) kept; an isolated vertex (5) has no edges.
TEST(EdgeTopology, NonManifoldEdgeKeepsTheFirstTwoFaces) {
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  expect_matches_sorted_reference(F, 6);
  const EdgeTopology t = edge_topology(F, 6);
  EXPECT_EQ(t.E(0, 0), 0);
  EXPECT_EQ(t.E(0, 1), 1);
  EXPECT_EQ(t.face_count(0), 3);
  EXPECT_EQ(t.EF(0, 0), 0);
  EXPECT_EQ(t.EF(0, 1), 1);
}

} // namespace

// Issue 20: a disc whose centre has valence 200K, faces listed in decreasing order, took 48.7 s (an
// insertion sort per vertex, quadratic in the valence); it must build in well under a second in Release.
// The timing itself is a benchmark (bench/edge_topology_bench.cpp, the 200K / 50K ratio); this checks the
// result against the sorted reference on the same input.
TEST(EdgeTopology, HighValenceDiscInDecreasingOrder) {
  const int n = 200000;
  Eigen::MatrixXi F(n, 3);
  for (int i = 0; i < n; ++i) {
    const int ring = n - 1 - i; // decreasing order
    F.row(i) << 0, 1 + ring, 1 + (ring + 1) % n;
  }
  expect_matches_sorted_reference(F, n + 1);
  const EdgeTopology t = edge_topology(F, n + 1);
  EXPECT_EQ(t.E.rows(), 2 * n);                      // n spokes + n rim edges
  EXPECT_EQ((t.face_count.array() == 1).count(), n); // the rim is the boundary
}
