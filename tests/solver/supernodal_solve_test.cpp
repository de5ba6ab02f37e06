// The hand-written supernodal triangular solves (src/solver/supernodal_solve.h) against a dense Cholesky
// solve and CHOLMOD's own solve, on one and several threads, for 1, 3 and 5 right-hand sides; and the
// schedules they run on: subtrees split over the threads where the elimination tree has them, nothing to
// split on a chain.
#include "iarap/core/threads.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/sparse_cholesky.h"
#include "solver/supernodal_solve.h"
#include "solver_fixtures.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <omp.h>

#include <random>
#include <vector>

namespace iarap {
namespace {

// CHOLMOD's supernodal factor of A, as SparseCholesky makes it (through Eigen's wrapper).
class Factor : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> {
public:
  explicit Factor(const Eigen::SparseMatrix<double>& A) {
    cholmod().print = 0;
    compute(A);
  }
  detail::SupernodalFactorView view() const {
    const auto v = detail::supernodal_factor_view(m_cholmodFactor);
    if (!v) throw std::runtime_error("not a supernodal LL^T factor");
    return *v;
  }
};

// Symmetric with off-diagonal entries in [-1, 1] on a random pattern (`neighbours` random partners per row)
// and diagonal 1 + the row's sum of |off-diagonal|: by Gershgorin every eigenvalue lies in
// [1, 1 + 2 max row sum], so A is positive definite and its condition number is below 1 + 4 * 2 * neighbours
// (a row has about 2 * neighbours partners, rarely twice that).
Eigen::SparseMatrix<double> random_spd(int n, int neighbours, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd diagonal = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; ++i)
    for (int m = 0; m < neighbours; ++m) {
      const int j = pick(rng);
      if (j == i) continue;
      const double a = value(rng);
      t.emplace_back(i, j, a);
      t.emplace_back(j, i, a);
      diagonal(i) += std::abs(a);
      diagonal(j) += std::abs(a);
    }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, diagonal(i));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// thread_count() for one scope, restored after.
class ThreadCount {
public:
  explicit ThreadCount(int n) : saved_(thread_count()) { set_thread_count(n); }
  ~ThreadCount() { set_thread_count(saved_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

private:
  int saved_;
};

double relative_difference(const Eigen::MatrixXd& X, const Eigen::MatrixXd& reference) {
  return (X - reference).norm() / reference.norm();
}

// Every supernode exactly once: in one bin or in the top part.
void expect_partition(const detail::SupernodalSchedule& sc, int nsuper) {
  std::vector<int> seen(nsuper, 0);
  for (const auto& bin : sc.bin_supernodes)
    for (const int s : bin) ++seen[s];
  for (const int s : sc.top) ++seen[s];
  for (int s = 0; s < nsuper; ++s) EXPECT_EQ(seen[s], 1) << "supernode " << s;
}

// Forward error against a dense Cholesky solve: both are backward stable, so they differ by at most about
// cond(A) * (a small multiple of n^(1/2) eps); cond(A) < 50 here (random_spd), n <= 400: 1e-12 leaves a
// wide margin and still fails any wrong update, which changes X at order 1.
TEST(SupernodalSolve, RandomMatricesMatchADenseSolve) {
  unsigned seed = 1;
  for (const int n : {2, 17, 120, 400}) {
    const Eigen::SparseMatrix<double> A = random_spd(n, 3, seed++);
    const Factor factor(A);
    ASSERT_EQ(factor.info(), Eigen::Success);
    const Eigen::LLT<Eigen::MatrixXd> dense{Eigen::MatrixXd(A)};
    for (const int threads : {1, 2, 3}) {
      // No overhead charged to a parallel schedule: these small trees are split too.
      detail::SupernodalSolve solve(factor.view(), threads, 0.0);
      ASSERT_TRUE(solve.usable());
      expect_partition(solve.schedule(), factor.view().nsuper);
      detail::SupernodalWorkspace ws;
      for (const int k : {1, 3, 5}) {
        const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, k);
        Eigen::MatrixXd X;
        solve.solve(B, X, threads, ws);
        EXPECT_LT(relative_difference(X, dense.solve(B)), 1e-12)
            << "n " << n << ", " << threads << " threads, " << k << " columns";
      }
    }
  }
}

// A grid's elimination tree branches: on two threads the schedule has subtrees and a top part, and
// the result equals the one-thread result to rounding (eigenvalues in [1, 9]: cond <= 9, so 1e-13 is a
// margin of ~50 over eps * cond) and is the same bit for bit from one call to the next.
TEST(SupernodalSolve, GridSplitsIntoSubtreesAndAgreesAcrossThreadCounts) {
  const Eigen::SparseMatrix<double> A = test::grid_laplacian(30, 1.0);
  const Factor factor(A);
  ASSERT_EQ(factor.info(), Eigen::Success);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  detail::SupernodalWorkspace ws;
  detail::SupernodalSolve one(factor.view(), 1, 0.0);
  EXPECT_EQ(one.schedule().bins, 1);
  Eigen::MatrixXd X1;
  one.solve(B, X1, 1, ws);
  EXPECT_LT((A * X1 - B).norm() / B.norm(), 1e-13);
  for (const int threads : {2, 3}) {
    detail::SupernodalSolve many(factor.view(), threads, 0.0);
    const detail::SupernodalSchedule& sc = many.schedule();
    EXPECT_EQ(sc.threads, threads);
    EXPECT_GE(sc.bins, threads);
    EXPECT_FALSE(sc.top.empty());
    expect_partition(sc, factor.view().nsuper);
    Eigen::MatrixXd X, again;
    many.solve(B, X, threads, ws);
    many.solve(B, again, threads, ws);
    EXPECT_EQ(X, again) << threads << " threads";
    EXPECT_LT(relative_difference(X, X1), 1e-13) << threads << " threads";
  }
}

// X may be B itself (LocalGlobalProblem solves in place): every row is gathered before any is scattered,
// and a group of columns scatters only its own columns, so the bits are those of a solve into another
// array, on one thread and on the split schedules, for one group of columns (3) and two (6 > 4).
TEST(SupernodalSolve, InPlaceGivesTheSameBits) {
  const Eigen::SparseMatrix<double> A = test::grid_laplacian(30, 1.0);
  const Factor factor(A);
  ASSERT_EQ(factor.info(), Eigen::Success);
  for (const int threads : {1, 2, 3})
    for (const int k : {3, 6}) {
      detail::SupernodalSolve solve(factor.view(), threads, 0.0);
      detail::SupernodalWorkspace ws;
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), k);
      Eigen::MatrixXd X, in_place = B;
      solve.solve(B, X, threads, ws);
      solve.solve(in_place, in_place, threads, ws);
      EXPECT_EQ(in_place, X) << threads << " threads, " << k << " columns";
    }
}

// Inside another parallel region the solve's team has one thread, which then does every part in turn:
// the same schedule, so the same bits as the solve on its own threads.
TEST(SupernodalSolve, InsideAParallelRegionGivesTheSameBits) {
  const Eigen::SparseMatrix<double> A = test::grid_laplacian(30, 1.0);
  const Factor factor(A);
  ASSERT_EQ(factor.info(), Eigen::Success);
  const detail::SupernodalSolve solve(factor.view(), 2, 0.0);
  ASSERT_GE(solve.schedule().bins, 2);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  Eigen::MatrixXd alone, nested[2];
  detail::SupernodalWorkspace ws;
  solve.solve(B, alone, 2, ws);
#pragma omp parallel num_threads(2)
  {
    detail::SupernodalWorkspace own; // const solves may run concurrently, each with its own workspace
    const int t = omp_get_thread_num();
    if (t < 2) solve.solve(B, nested[t], 2, own);
  }
  EXPECT_EQ(nested[0], alone);
  if (nested[1].size() > 0) { // the runtime may give the region one thread
    EXPECT_EQ(nested[1], alone);
  }
}

// A dense matrix: its elimination tree is a single chain, so no schedule splits it whatever the thread
// count; the solve is still right (cond < 50 as in random_spd: 1e-12).
TEST(SupernodalSolve, ChainHasNothingToSplit) {
  const int n = 40;
  Eigen::MatrixXd M = Eigen::MatrixXd::Random(n, n);
  M = (M + M.transpose()).eval();
  for (int i = 0; i < n; ++i) M(i, i) = 1.0 + M.row(i).cwiseAbs().sum();
  const Eigen::SparseMatrix<double> A = M.sparseView();
  const Factor factor(A);
  ASSERT_EQ(factor.info(), Eigen::Success);
  detail::SupernodalSolve solve(factor.view(), 2, 0.0);
  EXPECT_EQ(solve.schedule().bins, 1);
  EXPECT_TRUE(solve.schedule().top.empty());
  detail::SupernodalWorkspace ws;
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
  Eigen::MatrixXd X;
  solve.solve(B, X, 2, ws);
  EXPECT_LT(relative_difference(X, M.llt().solve(B)), 1e-12);
}

// Many tiny supernodes: a block-diagonal matrix of 1 x 1 and 2 x 2 blocks is a forest of one-block trees;
// two threads share them and nothing is left for a top part. The 1 x 1 blocks (value 4) solve
// exactly (x = b / 2 / 2); the 2 x 2 blocks [[2, 1], [1, 2]] have cond 3: 1e-15 relative per block.
TEST(SupernodalSolve, ManyTinySupernodesSplitWithoutTopPart) {
  std::vector<Eigen::Triplet<double>> t;
  int n = 0;
  std::vector<int> single;
  for (int block = 0; block < 200; ++block) {
    if (block % 3 == 0) {
      t.emplace_back(n, n, 2.0);
      t.emplace_back(n + 1, n + 1, 2.0);
      t.emplace_back(n, n + 1, 1.0);
      t.emplace_back(n + 1, n, 1.0);
      n += 2;
    } else {
      single.push_back(n);
      t.emplace_back(n, n, 4.0);
      n += 1;
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  const Factor factor(A);
  ASSERT_EQ(factor.info(), Eigen::Success);
  detail::SupernodalSolve solve(factor.view(), 2, 0.0);
  EXPECT_EQ(solve.schedule().threads, 2);
  EXPECT_GE(solve.schedule().bins, 2);
  EXPECT_TRUE(solve.schedule().top.empty());
  expect_partition(solve.schedule(), factor.view().nsuper);
  detail::SupernodalWorkspace ws;
  for (const int k : {1, 3, 5}) {
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, k);
    Eigen::MatrixXd X;
    solve.solve(B, X, 2, ws);
    for (const int i : single) EXPECT_EQ(X.row(i), B.row(i) / 4.0) << "row " << i;
    EXPECT_LT((A * X - B).norm() / B.norm(), 1e-15 * n);
  }
}

// SparseCholesky on a 1 x 1 matrix: L = [2], so X = B / 4 exactly, on one thread and two.
TEST(SupernodalSolve, OneByOneThroughSparseCholesky) {
  Eigen::SparseMatrix<double> A(1, 1);
  A.insert(0, 0) = 4.0;
  SparseCholesky chol(A);
  ASSERT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(1, 3);
  for (const int threads : {1, 2}) {
    const ThreadCount guard(threads);
    Eigen::MatrixXd X;
    chol.solve(B, X);
    EXPECT_EQ(X, B / 4.0) << threads << " threads";
    EXPECT_EQ(chol.solve(B), B / 4.0) << threads << " threads";
  }
}

// The ARAP global step's own matrix (bunny, L_ff of the cotan system with a few vertices fixed) through
// SparseCholesky: solve and CHOLMOD's solve, 1 and 2 threads, 1, 3 and 5 columns. Both are backward stable:
// the relative residual |A X - B| / (|A| |X|) stays within a small multiple of eps (1e-14 is ~45 eps), and
// the two solutions differ by at most about cond(A) times that; cond(A) is estimated by power iterations
// with A and with the solve (an underestimate, hence the factor 10 in the bound).
TEST(SupernodalSolve, ArapSystemOfTheBunnyMatchesCholmod) {
  const test::SolverMesh m = test::bunny();
  Eigen::VectorXi fixed(6);
  for (int i = 0; i < 6; ++i) fixed(i) = i * static_cast<int>(m.V.rows() / 6);
  ArapOptions options;
  options.method = ArapMethod::Arap;
  const ArapData data = arap_precompute(m.V, m.F, fixed, options);
  const int n = static_cast<int>(data.free.size());
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < data.L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(data.L, k); it; ++it)
      if (data.free_slot(it.row()) >= 0 && data.free_slot(it.col()) >= 0)
        t.emplace_back(data.free_slot(it.row()), data.free_slot(it.col()), it.value());
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  SparseCholesky chol(A);
  ASSERT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);

  Eigen::VectorXd v = Eigen::VectorXd::Ones(n), w = v;
  const ThreadCount one(1); // many small solves: a team would only wait at their barriers
  for (int it = 0; it < 30; ++it) {
    v = (A * v).normalized();
    w = chol.solve(Eigen::MatrixXd(w)).col(0).normalized();
  }
  const double largest = v.dot(A * v), smallest = w.dot(A * w);
  const double cond = largest / smallest;
  const double A_norm = largest; // the 2-norm of the symmetric positive definite A

  for (const int threads : {1, 2}) {
    const ThreadCount guard(threads);
    for (const int k : {1, 3, 5}) {
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, k);
      Eigen::MatrixXd X, Xc;
      chol.solve(B, X);
      chol.solve_with_cholmod(B, Xc);
      EXPECT_LT((A * X - B).norm() / (A_norm * X.norm()), 1e-14)
          << threads << " threads, " << k << " columns";
      EXPECT_LT(relative_difference(X, Xc), 10 * cond * 1e-14)
          << threads << " threads, " << k << " columns, cond " << cond;
      EXPECT_EQ(chol.solve(B), X) << "the allocating solve, " << threads << " threads";
    }
  }
}

} // namespace
} // namespace iarap
