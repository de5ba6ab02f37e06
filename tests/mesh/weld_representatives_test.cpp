// weld_representatives against an independent O(n^2) derivation (every pair within the tolerance, joined
// by a union-find of its own), and the inputs that made the old grid quadratic: one outlier at 1e30, a
// whole mesh at one point.
#include "iarap/mesh/validate.h"
#include "iarap/mesh/weld_representatives.h"
#include "intrinsic/mesh_generators.h"

#include <cmath>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <vector>

namespace {

// The smallest index of each cluster of finite points joined by pairs within the tolerance.
Eigen::VectorXi brute_force_representatives(const Eigen::MatrixXd& V, double tolerance) {
  const int n = static_cast<int>(V.rows());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)];
    return x;
  };
  // Row-major copies and the finite rows, so that the n^2 / 2 pairs cost a few flops each: a pair apart by
  // more than the tolerance in one coordinate is farther than it (the norm bounds each coordinate's
  // difference), and only the others are measured.
  std::vector<double> p(static_cast<std::size_t>(3 * n));
  std::vector<char> finite(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) p[static_cast<std::size_t>(3 * i + d)] = V(i, d);
    finite[static_cast<std::size_t>(i)] = V.row(i).allFinite();
  }
  const auto apart_in_a_coordinate = [&](int i, int j) {
    for (int d = 0; d < 3; ++d)
      if (std::abs(p[static_cast<std::size_t>(3 * i + d)] - p[static_cast<std::size_t>(3 * j + d)]) >
          tolerance)
        return true;
    return false;
  };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (!finite[static_cast<std::size_t>(i)] || !finite[static_cast<std::size_t>(j)]) continue;
      if (apart_in_a_coordinate(i, j)) continue;
      const bool close =
          tolerance > 0 ? (V.row(i) - V.row(j)).stableNorm() <= tolerance : V.row(i) == V.row(j);
      if (!close) continue;
      const int a = root(i), b = root(j);
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  Eigen::VectorXi r(n);
  for (int i = 0; i < n; ++i) r(i) = root(i);
  return r;
}

// Clusters of points around random centres, spread over a few tolerances, with exact copies, so that
// every case of the grid occurs: whole cells, neighbour cells joined and not, chains across cells.
Eigen::MatrixXd clustered_cloud(int n, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(-1.0, 1.0);
  Eigen::MatrixXd V(n, 3);
  Eigen::RowVector3d centre(0, 0, 0);
  for (int i = 0; i < n; ++i) {
    if (i % 7 == 0) centre << u(rng), u(rng), u(rng);
    if (i % 11 == 5) {
      V.row(i) = V.row(i - 1); // an exact copy
      continue;
    }
    V.row(i) = centre + spread * Eigen::RowVector3d(w(rng), w(rng), w(rng));
  }
  return V;
}

} // namespace

TEST(WeldRepresentatives, MatchesAllPairsOnClusteredClouds) {
  for (unsigned seed = 1; seed <= 4; ++seed)
    for (const double tolerance : {1e-3, 4e-3, 2e-2, 0.3}) {
      const Eigen::MatrixXd V = clustered_cloud(700, 5e-3, seed);
      EXPECT_EQ(iarap::weld_representatives(V, tolerance), brute_force_representatives(V, tolerance))
          << "seed " << seed << ", tolerance " << tolerance;
    }
}

// Below 1e-13 of the extent the cells are coarser than the tolerance and pairs inside them are tested one
// by one; the result is the same.
TEST(WeldRepresentatives, MatchesAllPairsAtTinyRelativeTolerances) {
  Eigen::MatrixXd V = clustered_cloud(300, 1e-15, 7);
  V.row(0) << 1e3, 1e3, 1e3; // extent 1e3: the tolerances below are < 1e-17 of it
  for (const double tolerance : {1e-16, 5e-16, 2e-15})
    EXPECT_EQ(iarap::weld_representatives(V, tolerance), brute_force_representatives(V, tolerance))
        << tolerance;
}

// Two dense lines of points in neighbouring cells whose boxes lie within the tolerance of each other
// while the closest pair is just beyond it (d = 0.65: 1.011 x tolerance) or just within (d = 0.55: 0.980
// x): the case the median split of the cells decides.
TEST(WeldRepresentatives, DenseCellsWithCloseBoxes) {
  const int n = 1500;
  for (const double d : {0.65, 0.55}) {
    Eigen::MatrixXd V(2 * n, 3);
    for (int i = 0; i < n; ++i) {
      const double t = 0.5 * i / (n - 1);
      V.row(i) << 0.0, t, t;
      V.row(n + i) << 0.9, t, t + d;
    }
    const Eigen::VectorXi r = iarap::weld_representatives(V, 1.0);
    EXPECT_EQ(r, brute_force_representatives(V, 1.0)) << d;
    EXPECT_EQ(r(2 * n - 1), d < 0.6 ? 0 : n) << d;
  }
}

TEST(WeldRepresentatives, ExactModeAndNonFinite) {
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 0, 0, 1e-300, NAN, 0, 0, 0, 0, 0, NAN, 0, 0;
  const Eigen::VectorXi r = iarap::weld_representatives(V, 0.0);
  Eigen::VectorXi expected(5);
  expected << 0, 1, 2, 0, 4;
  EXPECT_EQ(r, expected);
}

// Issue 20: 20K copies of one point (a pile a broken exporter leaves) weld through the position sort, not
// a pairwise search quadratic in such a pile; the result names the smallest index.
TEST(WeldRepresentatives, PileOfIdenticalPointsWelds) {
  const int n = 20000;
  Eigen::MatrixXd V = Eigen::MatrixXd::Constant(n, 3, 0.25);
  V.row(n - 1) << 1, 1, 1; // one point elsewhere, so the bounding box is not empty
  const Eigen::VectorXi r = iarap::weld_representatives(V, 1e-12);
  EXPECT_EQ((r.head(n - 1).array() == 0).count(), n - 1);
  EXPECT_EQ(r(n - 1), n - 1);
}

// Issue 33: one vertex at 1e30 makes the tolerance (1e-12 x diagonal) 1e18, so the whole 40K sheet lies
// in one cell of the old grid and its pair search was quadratic (over 60 s). The sheet is one cluster
// now, found by joining the cell whole; the outlier stays alone.
TEST(WeldRepresentatives, OneOutlierAt1e30ReportsTheSheetAsOnePoint) {
  iarap::test::TestMesh m = iarap::test::planar_grid(199); // 200 x 200 vertices
  const int outlier = 12345;
  m.V.row(outlier) << 1e30, 0, 0;
  const iarap::MeshReport r = iarap::check_mesh(m.V, m.F);
  EXPECT_EQ(r.coincident_vertices, 40000 - 2); // all but the first sheet vertex and the outlier
  EXPECT_NEAR(r.bbox_diagonal, 1e30, 1e16);
  const Eigen::VectorXi rep = iarap::weld_representatives(m.V, 1e-12 * r.bbox_diagonal);
  EXPECT_EQ(rep(outlier), outlier);
  EXPECT_EQ((rep.array() == 0).count(), 40000 - 1);
}

// Issue 33: 150K vertices at one point: every face has zero area, every vertex but the first coincides.
TEST(WeldRepresentatives, AllVerticesAtOnePoint) {
  iarap::test::TestMesh m = iarap::test::planar_grid(387); // 388^2 = 150544 vertices
  m.V.setConstant(0.25);
  const iarap::MeshReport r = iarap::check_mesh(m.V, m.F);
  EXPECT_EQ(r.coincident_vertices, m.V.rows() - 1);
  EXPECT_EQ(r.zero_area_faces, m.F.rows());
  EXPECT_EQ(r.bbox_diagonal, 0.0);
}
