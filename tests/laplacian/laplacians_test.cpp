// Tests of the Laplace-Beltrami operators of paper Section 6: zero row sums, agreement on Delaunay meshes,
// linear precision on flat non-Delaunay meshes, sparsity.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/laplacian/laplacians.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"
#include "intrinsic/mesh_generators.h"
#include "laplacian/sparse_norms.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace iarap {
namespace {

using test::max_abs;
using test::max_abs_diagonal;

// A flat jittered grid with random convex flips: a valid planar embedding far from Delaunay.
test::TestMesh flipped_grid() {
  test::TestMesh m = test::planar_grid(12, 0.3, 3);
  test::random_planar_flips(m, 120, 11);
  return m;
}

int negative_cotan_weights(const test::TestMesh& m) {
  const Eigen::SparseMatrix<double> L = cotan_laplacian(m.V, m.F);
  int count = 0;
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it)
      if (it.row() < it.col() && it.value() > 0) ++count;
  return count;
}

TEST(LaplacianKind, NamesRoundTripAndUnknownIsNamed) {
  for (LaplacianKind kind : all_laplacian_kinds())
    EXPECT_EQ(parse_laplacian_kind(laplacian_kind_name(kind)), kind);
  try {
    parse_laplacian_kind("iarap+");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'iarap+'"), std::string::npos) << e.what();
  }
}

// Rows sum to zero (constants in the kernel) for every operator, 1e-12 relative to max |L_ii|: each row
// sum adds a handful of terms bounded by max |L_ii|, each with ~1e-16 relative round-off.
void expect_zero_row_sums(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& mesh) {
  const IntrinsicDelaunay idt = intrinsic_delaunay(V, F);
  for (LaplacianKind kind : all_laplacian_kinds()) {
    const Eigen::SparseMatrix<double> L = laplacian(V, F, kind, &idt);
    const Eigen::VectorXd row_sums = L * Eigen::VectorXd::Ones(V.rows());
    EXPECT_LE(row_sums.cwiseAbs().maxCoeff(), 1e-12 * max_abs_diagonal(L))
        << mesh << " " << laplacian_kind_name(kind);
  }
}

TEST(Laplacians, RowsSumToZeroOnBunny) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  expect_zero_row_sums(bunny.V, bunny.F, "bunny");
}

TEST(Laplacians, RowsSumToZeroOnFlatNonDelaunayGrid) {
  const test::TestMesh m = flipped_grid();
  expect_zero_row_sums(m.V, m.F, "flipped grid");
}

// On a Delaunay mesh every intrinsic edge is an input edge with one segment (sigma = 1, p = v_j), so all
// operators are the cotan Laplacian up to round-off in the weights.
void expect_all_equal_cotan(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& mesh) {
  const Eigen::SparseMatrix<double> cotan = cotan_laplacian(V, F);
  const IntrinsicDelaunay idt = intrinsic_delaunay(V, F);
  ASSERT_EQ(idt.triangulation.flips, 0) << mesh << " is expected to be Delaunay";
  const double scale = max_abs_diagonal(cotan);
  for (LaplacianKind kind : all_laplacian_kinds()) {
    const Eigen::SparseMatrix<double> L = laplacian(V, F, kind, &idt);
    EXPECT_LE(max_abs(L - cotan), 1e-12 * scale) << mesh << " " << laplacian_kind_name(kind);
  }
}

TEST(Laplacians, EqualCotanOnDelaunayGrid) {
  const test::TestMesh m = test::planar_grid(10);
  expect_all_equal_cotan(m.V, m.F, "regular grid");
}

TEST(Laplacians, EqualCotanOnDelaunayCube) {
  IARAP_SHARED_MESH_OR_SKIP(path, "cube.obj");
  const MeshData cube = read_mesh(path);
  expect_all_equal_cotan(cube.V, cube.F, "cube.obj");
}

// B^T D_w B equals the cotan Laplacian on every mesh: operator_identity_test.cpp.

// max over interior vertices of |(L x)_i|, |(L y)_i| relative to max |L_ii| * bbox diagonal.
double linear_residual(const test::TestMesh& m, const Eigen::SparseMatrix<double>& L) {
  const EdgeTopology topology = edge_topology(m.F, static_cast<int>(m.V.rows()));
  std::vector<char> boundary(static_cast<size_t>(m.V.rows()), 0);
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e)
    if (topology.face_count(e) == 1) boundary[topology.E(e, 0)] = boundary[topology.E(e, 1)] = 1;
  const Eigen::MatrixXd Lxy = L * m.V.leftCols(2);
  double residual = 0;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    if (!boundary[static_cast<size_t>(i)]) residual = std::max(residual, Lxy.row(i).cwiseAbs().maxCoeff());
  const double diagonal = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  return residual / (max_abs_diagonal(L) * diagonal);
}

// Linear precision (paper Section 6): for the traced operators the proof telescopes along each straight
// polyline; round-off in the traced crossing parameters bounds the residual well below 1e-10.
TEST(Laplacians, LinearPrecisionOnFlatNonDelaunayGrid) {
  for (unsigned seed : {3u, 5u, 8u}) {
    test::TestMesh m = test::planar_grid(12, 0.3, seed);
    test::random_planar_flips(m, 120, seed + 10);
    ASSERT_GT(negative_cotan_weights(m), 5) << "the fixture must be non-Delaunay (seed " << seed << ")";
    const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
    ASSERT_GT(idt.triangulation.flips, 0);
    for (LaplacianKind kind :
         {LaplacianKind::Cotan, LaplacianKind::Intrinsic, LaplacianKind::Iarap, LaplacianKind::IarapPlus})
      EXPECT_LE(linear_residual(m, laplacian(m.V, m.F, kind, &idt)), 1e-10)
          << laplacian_kind_name(kind) << " seed " << seed;
    // The first-segment symmetric operator drops the segments that telescope away the crossing terms,
    // so it is not linearly precise (see first_segment_laplacians.h): a residual far above round-off.
    EXPECT_GT(linear_residual(m, laplacian(m.V, m.F, LaplacianKind::IarapSym, &idt)), 1e-6)
        << "seed " << seed;
  }
}

// Every operator but the intrinsic one couples only vertices of a common input face (Eq. 17: b has
// its nonzeros on one face); on a flat triangulation these are exactly the input edges.
TEST(Laplacians, TracedOperatorsHaveInputSparsity) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const IntrinsicDelaunay idt = intrinsic_delaunay(bunny.V, bunny.F);
  const EdgeTopology topology = edge_topology(bunny.F, static_cast<int>(bunny.V.rows()));
  Eigen::SparseMatrix<double> adjacency(bunny.V.rows(), bunny.V.rows());
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e) {
    triplets.emplace_back(topology.E(e, 0), topology.E(e, 1), 1.0);
    triplets.emplace_back(topology.E(e, 1), topology.E(e, 0), 1.0);
  }
  for (Eigen::Index i = 0; i < bunny.V.rows(); ++i) triplets.emplace_back(i, i, 1.0);
  adjacency.setFromTriplets(triplets.begin(), triplets.end());
  for (LaplacianKind kind : {LaplacianKind::Iarap, LaplacianKind::IarapPlus, LaplacianKind::IarapSym}) {
    const Eigen::SparseMatrix<double> L = laplacian(bunny.V, bunny.F, kind, &idt);
    int outside = 0;
    for (int k = 0; k < L.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it)
        if (it.value() != 0.0 && adjacency.coeff(it.row(), it.col()) == 0.0) ++outside;
    EXPECT_EQ(outside, 0) << laplacian_kind_name(kind);
  }
}

// The intrinsic Laplacian on the bunny has edges the input lacks (flipped ones); its weights equal the
// triangulation's and it is symmetric.
TEST(Laplacians, IntrinsicMatchesTriangulationWeights) {
  const MeshData bunny = read_mesh(test::data_path("bunny.off"));
  const IntrinsicDelaunay idt = intrinsic_delaunay(bunny.V, bunny.F);
  ASSERT_GT(idt.triangulation.flips, 0);
  const Eigen::SparseMatrix<double> L = laplacian(bunny.V, bunny.F, LaplacianKind::Intrinsic, &idt);
  EXPECT_EQ(max_abs(L - Eigen::SparseMatrix<double>(L.transpose())), 0.0);
  const auto& T = idt.triangulation;
  Eigen::SparseMatrix<double> expected(bunny.V.rows(), bunny.V.rows());
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index e = 0; e < T.E.rows(); ++e)
    if (T.E(e, 0) != T.E(e, 1)) {
      triplets.emplace_back(T.E(e, 0), T.E(e, 1), -T.cot_weight(e));
      triplets.emplace_back(T.E(e, 1), T.E(e, 0), -T.cot_weight(e));
    }
  expected.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseMatrix<double> off_diagonal = L;
  off_diagonal.prune([](Eigen::Index r, Eigen::Index c, double) { return r != c; });
  EXPECT_LE(max_abs(off_diagonal - expected), 1e-14 * max_abs_diagonal(L));
}

// L+ on an intrinsic edge that is an input edge: its first segment is the whole edge, p = v_j, and the
// entry is the intrinsic cotan weight -w_ij, unless another first segment from i ends on an input edge
// at j. On the flipped grid check every pair (i, j) that only such a single-segment edge touches.
TEST(Laplacians, IarapPlusGivesCotanWeightOnUnsplitEdges) {
  const test::TestMesh m = flipped_grid();
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  const Eigen::SparseMatrix<double> L_plus = laplacian(m.V, m.F, LaplacianKind::IarapPlus, &idt);
  const auto& T = idt.triangulation;
  const auto& traces = idt.traces;
  // Count, per (row i, column j), the first segments from i whose far point involves j.
  Eigen::SparseMatrix<double> touches(m.V.rows(), m.V.rows());
  std::vector<Eigen::Triplet<double>> triplets;
  for (Eigen::Index e = 0; e < T.E.rows(); ++e)
    for (int end = 0; end < 2; ++end) {
      const size_t p = static_cast<size_t>(end == 0 ? traces.start[e] + 1 : traces.start[e + 1] - 2);
      triplets.emplace_back(T.E(e, end), traces.a[p], 1.0);
      if (traces.c[p] >= 0) triplets.emplace_back(T.E(e, end), traces.c[p], 1.0);
    }
  touches.setFromTriplets(triplets.begin(), triplets.end());
  int checked = 0;
  for (Eigen::Index e = 0; e < T.E.rows(); ++e) {
    if (traces.start[e + 1] - traces.start[e] != 2) continue;
    const int i = T.E(e, 0), j = T.E(e, 1);
    if (touches.coeff(i, j) != 1.0) continue;
    EXPECT_NEAR(L_plus.coeff(i, j), -T.cot_weight(e), 1e-14 * max_abs_diagonal(L_plus)) << "edge " << e;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(Laplacians, MismatchedPrecomputedTriangulationIsInputError) {
  const test::TestMesh small = test::planar_grid(3), large = test::planar_grid(4);
  const IntrinsicDelaunay idt = intrinsic_delaunay(small.V, small.F);
  EXPECT_THROW(laplacian(large.V, large.F, LaplacianKind::Iarap, &idt), InputError);
}

} // namespace
} // namespace iarap
