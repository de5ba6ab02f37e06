#include "iarap/solver/system_pattern.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <tuple>
#include <vector>

namespace {

using namespace iarap;

// The pattern holds exactly the diagonal and the mesh edges, with sorted rows, and every face slot
// points at its (row, column).
TEST(SystemPattern, HoldsTheDiagonalAndTheEdgesWithFaceSlots) {
  const auto m = test::bumpy_patch(6);
  const int n = static_cast<int>(m.V.rows());
  const SystemPattern p = system_pattern(m.F, n);
  const EdgeTopology topo = edge_topology(m.F, n);
  ASSERT_TRUE(p.matrix.isCompressed());
  EXPECT_EQ(p.matrix.nonZeros(), n + 2 * topo.E.rows());
  std::set<std::pair<int, int>> expected;
  for (int v = 0; v < n; ++v) expected.insert({v, v});
  for (int e = 0; e < topo.E.rows(); ++e) {
    expected.insert({topo.E(e, 0), topo.E(e, 1)});
    expected.insert({topo.E(e, 1), topo.E(e, 0)});
  }
  std::set<std::pair<int, int>> got;
  for (int j = 0; j < n; ++j)
    for (int k = p.matrix.outerIndexPtr()[j]; k < p.matrix.outerIndexPtr()[j + 1]; ++k) {
      got.insert({p.matrix.innerIndexPtr()[k], j});
      if (k > p.matrix.outerIndexPtr()[j]) {
        EXPECT_LT(p.matrix.innerIndexPtr()[k - 1], p.matrix.innerIndexPtr()[k]);
      }
    }
  EXPECT_EQ(got, expected);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const int slot = p.face_slot(f, 3 * k + l);
        ASSERT_GE(slot, 0);
        EXPECT_EQ(p.matrix.innerIndexPtr()[slot], m.F(f, k));
        EXPECT_TRUE(slot >= p.matrix.outerIndexPtr()[m.F(f, l)] &&
                    slot < p.matrix.outerIndexPtr()[m.F(f, l) + 1]);
      }
}

// Summing on the pattern gives the triplet assembly's matrix for all three variants (only the summation
// order differs: 1e-14 relative), bitwise symmetric.
TEST(SystemPattern, AssemblyMatchesTheTripletSum) {
  for (const auto& m : {test::bunny(), test::bumpy_patch(12)}) {
    const SystemPattern p = system_pattern(m.F, static_cast<int>(m.V.rows()));
    IntrinsicOptions refine;
    refine.refine_boundary = true;
    for (const ArapElements& el : {arap_edge_elements(m.V, m.F), spokes_rims_elements(m.V, m.F),
                                   iarap_elements(m.V, intrinsic_delaunay(m.V, m.F)),
                                   iarap_elements(m.V, intrinsic_delaunay(m.V, m.F, refine))}) {
      const Eigen::SparseMatrix<double> L = element_system_matrix(el, m.F, p);
      const Eigen::SparseMatrix<double> reference = element_system_matrix(el);
      EXPECT_LT((L - reference).norm(), 1e-14 * reference.norm());
      const Eigen::SparseMatrix<double> Lt = L.transpose();
      EXPECT_EQ((L - Lt).norm(), 0.0);
    }
  }
}

TEST(SystemPattern, ElementOffItsFaceIsNamed) {
  const auto m = test::bumpy_patch(3);
  const SystemPattern p = system_pattern(m.F, static_cast<int>(m.V.rows()));
  ArapElements el = arap_edge_elements(m.V, m.F);
  el.face[5] = (el.face[5] + 7) % static_cast<int>(m.F.rows()); // a face that does not hold edge 5
  bool holds = false;
  for (int k = 0; k < 3; ++k) holds |= m.F(el.face[5], k) == el.b_index(5, 0);
  if (holds) el.face[5] = (el.face[5] + 5) % static_cast<int>(m.F.rows());
  try {
    element_system_matrix(el, m.F, p);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element 5"), std::string::npos) << e.what();
  }
  el.face[5] = -1;
  EXPECT_THROW(element_system_matrix(el, m.F, p), InputError);
}

// The symbolic analysis overlapped with the element build (more than one thread) and the sequential path
// (one thread) factorize the same matrix: identical positions after the same iterations.
TEST(SystemPattern, OverlappedAnalysisGivesTheSequentialResult) {
  const auto m = test::bumpy_patch(16);
  const int n = static_cast<int>(m.V.rows());
  Eigen::VectorXi fixed(4);
  fixed << 0, 1, n - 2, n - 1;
  Eigen::MatrixXd targets(4, 3);
  for (int k = 0; k < 4; ++k) targets.row(k) = m.V.row(fixed(k));
  targets.bottomRows(2).col(2).array() += 0.3;
  ArapSolveOptions solve;
  solve.max_iterations = 5;
  solve.tolerance = -1;
  const int threads = thread_count();
  std::vector<Eigen::MatrixXd> results;
  for (int t : {1, 2}) {
    set_thread_count(t);
    ArapData data = arap_precompute(m.V, m.F, fixed);
    Eigen::MatrixXd U = m.V;
    arap_solve(data, targets, U, solve);
    results.push_back(U);
    EXPECT_EQ(data.timings.analyze_ms > 0.0, true);
  }
  set_thread_count(threads);
  EXPECT_LT((results[0] - results[1]).norm(), 1e-12 * test::bbox_diagonal(m.V));
}

} // namespace
