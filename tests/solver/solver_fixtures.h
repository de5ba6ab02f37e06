// Meshes for the solver tests: the bundled bunny, a small bumpy patch built in code, a mesh doubled
// into two disjoint components, and axis-band constraint sets; a grid Laplacian for the factorization tests.
#pragma once
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/solver/arap_types.h"
#include "test_support.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace iarap::test {

// Tests on meshes of a few thousand vertices or fewer run with one thread: there a thread team costs more
// than it saves (and on a loaded machine its barriers cost whole time slices, many times per solve).
class SingleThreadTest : public ::testing::Test {
protected:
  void SetUp() override { set_thread_count(1); }
  void TearDown() override { set_thread_count(0); }
};

// The three energies, for tests that run each.
inline constexpr ArapMethod kAllMethods[] = {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap};

// Plain iterations and the three accelerators that run alone (the hybrid chains two of them).
inline constexpr ArapAccelerator kPlainAndAccelerators[] = {ArapAccelerator::None, ArapAccelerator::Anderson,
                                                            ArapAccelerator::Lbfgs, ArapAccelerator::Newton};

// The largest distance between corresponding rows of A and B.
inline double max_row_distance(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).rowwise().norm().maxCoeff();
}

struct SolverMesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

inline SolverMesh bunny() {
  MeshData m = read_mesh(data_path("bunny.off"));
  return {m.V, m.F};
}

// n x n grid over [0,1]^2 lifted to a height field z = 0.3 sin(3x) cos(2y), vertices jittered in-plane and
// each square split along a random diagonal: curved, with boundary and (through the jitter and diagonals)
// some non-Delaunay edges.
inline SolverMesh bumpy_patch(int n, unsigned seed = 3) {
  SolverMesh m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.25, 0.25);
  std::bernoulli_distribution coin(0.5);
  m.V.resize((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = (i + (i > 0 && i < n ? u(rng) : 0.0)) / n,
                   y = (j + (j > 0 && j < n ? u(rng) : 0.0)) / n;
      m.V.row(j * (n + 1) + i) << x, y, 0.3 * std::sin(3 * x) * std::cos(2 * y);
    }
  m.F.resize(2 * n * n, 3);
  int f = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      if (coin(rng)) {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << a, d, c;
      } else {
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      }
    }
  return m;
}

// A patch of the triangular lattice (n x n vertices, near-equilateral faces) lifted to the gentle height
// field z = 0.15 sin(2x) cos(2y): every angle stays near 60 degrees, so all cotangent weights are positive
// (a Delaunay mesh, where original ARAP is well behaved).
inline SolverMesh lattice_patch(int n) {
  SolverMesh m;
  m.V.resize(n * n, 3);
  const double h = 1.0 / (n - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5 * (j % 2)) * h, y = j * h * std::sqrt(3.0) / 2.0;
      m.V.row(j * n + i) << x, y, 0.15 * std::sin(2 * x) * std::cos(2 * y);
    }
  m.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      if (j % 2 == 0) { // the row above is shifted right
        m.F.row(f++) << a, b, c;
        m.F.row(f++) << b, d, c;
      } else {
        m.F.row(f++) << a, b, d;
        m.F.row(f++) << a, d, c;
      }
    }
  return m;
}

// The mesh and a translated copy of it, as one mesh with two connected components.
inline SolverMesh two_copies(const SolverMesh& m) {
  SolverMesh out;
  const Eigen::Index n = m.V.rows();
  out.V.resize(2 * n, 3);
  out.V << m.V, m.V.rowwise() + Eigen::RowVector3d(2.0, 0.0, 0.0);
  out.F.resize(2 * m.F.rows(), 3);
  out.F << m.F, (m.F.array() + static_cast<int>(n)).matrix();
  return out;
}

// Vertices in the lowest (side < 0) or highest (side > 0) `fraction` of the bounding box along axis.
inline std::vector<int> axis_band(const Eigen::MatrixXd& V, int axis, double fraction, int side) {
  const double lo = V.col(axis).minCoeff(), hi = V.col(axis).maxCoeff();
  std::vector<int> out;
  for (int v = 0; v < V.rows(); ++v) {
    const double t = (V(v, axis) - lo) / (hi - lo);
    if ((side < 0 && t <= fraction) || (side > 0 && t >= 1.0 - fraction)) out.push_back(v);
  }
  return out;
}

inline Eigen::VectorXi to_vector(const std::vector<int>& v) {
  return Eigen::Map<const Eigen::VectorXi>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// The lowest and the highest `fraction` along axis as one constrained set, the low band first (low_count
// vertices): a bar held at both ends.
inline Eigen::VectorXi both_ends(const Eigen::MatrixXd& V, int axis, double fraction,
                                 Eigen::Index& low_count) {
  const Eigen::VectorXi low = to_vector(axis_band(V, axis, fraction, -1));
  const Eigen::VectorXi high = to_vector(axis_band(V, axis, fraction, +1));
  Eigen::VectorXi out(low.size() + high.size());
  out << low, high;
  low_count = low.size();
  return out;
}

// Rows `idx` of V.
inline Eigen::MatrixXd rows_of(const Eigen::MatrixXd& V, const Eigen::VectorXi& idx) {
  Eigen::MatrixXd out(idx.size(), V.cols());
  for (Eigen::Index k = 0; k < idx.size(); ++k) out.row(k) = V.row(idx(k));
  return out;
}

inline double bbox_diagonal(const Eigen::MatrixXd& V) {
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

// The n^2-vertex grid graph Laplacian (4-neighbourhood) plus `shift` on the diagonal: eigenvalues in
// (shift, 8 + shift), positive definite for shift > 0.
inline Eigen::SparseMatrix<double> grid_laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int v = i * n + j;
      t.emplace_back(v, v, 4.0 + shift);
      for (const int w : {i + 1 < n ? v + n : -1, j + 1 < n ? v + 1 : -1})
        if (w >= 0) {
          t.emplace_back(v, w, -1.0);
          t.emplace_back(w, v, -1.0);
        }
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

} // namespace iarap::test
