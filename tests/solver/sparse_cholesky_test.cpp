#include "iarap/solver/sparse_cholesky.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "solver_fixtures.h"

#include <omp.h>

#include <gtest/gtest.h>
#include <vector>

namespace {

using iarap::FactorizationKind;
using iarap::SparseCholesky;

// 1D Laplacian of a path with n vertices, end 0 fixed (Dirichlet), plus `shift` on the diagonal.
Eigen::SparseMatrix<double> path_laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// The 5-point Laplacian of an n x n grid plus `shift` on the diagonal (positive definite for shift > 0).
Eigen::SparseMatrix<double> grid_laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i + 1 < n) {
        t.emplace_back(id(i, j), id(i + 1, j), -1.0);
        t.emplace_back(id(i + 1, j), id(i, j), -1.0);
      }
      if (j + 1 < n) {
        t.emplace_back(id(i, j), id(i, j + 1), -1.0);
        t.emplace_back(id(i, j + 1), id(i, j), -1.0);
      }
    }
  Eigen::SparseMatrix<double> A(n * n, n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

double residual(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  return (A * X - B).norm() / B.norm();
}

TEST(SparseCholesky, PositiveDefiniteUsesCholmod) {
  const auto A = path_laplacian(200, 0.0);
  const SparseCholesky chol(A);
  EXPECT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(200, 3);
  EXPECT_LT(residual(A, chol.solve(B), B), 1e-12);
}

// The workspace solve (cholmod_solve2, reused between calls) gives bitwise the allocating solve's X, call
// after call, for both factorizations and for a change of the right-hand side count.
TEST(SparseCholesky, WorkspaceSolveEqualsTheAllocatingSolve) {
  for (const double shift : {0.0, -1.0 + 1e-3}) {
    const auto A = path_laplacian(120, shift);
    SparseCholesky chol(A);
    Eigen::MatrixXd X;
    for (const int columns : {3, 3, 1, 3}) {
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(120, columns);
      chol.solve(B, X);
      EXPECT_EQ(X, chol.solve(B)) << iarap::factorization_name(chol.kind()) << ", " << columns << " columns";
    }
    EXPECT_THROW(chol.solve(Eigen::MatrixXd::Zero(7, 3), X), iarap::SolverError);
  }
}

// X may be B: the in-place solve (and CHOLMOD's, through its own workspace) gives the bits of a solve into
// another array, for both factorizations.
TEST(SparseCholesky, InPlaceSolveEqualsTheOutOfPlaceOne) {
  for (const double shift : {0.0, -1.0 + 1e-3}) {
    SparseCholesky chol(path_laplacian(120, shift));
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(120, 3);
    Eigen::MatrixXd X, in_place = B, cholmod_in_place = B;
    chol.solve(B, X);
    chol.solve(in_place, in_place);
    EXPECT_EQ(in_place, X) << iarap::factorization_name(chol.kind());
    chol.solve_with_cholmod(B, X);
    chol.solve_with_cholmod(cholmod_in_place, cholmod_in_place);
    EXPECT_EQ(cholmod_in_place, X) << iarap::factorization_name(chol.kind());
  }
}

// B and X in another row order than A's (row r is A's row a_row[r]): the gathered solve gives the bits of
// reordering B by hand, solving and reordering X back, also in place, at one and at two threads (a grid
// big enough for a parallel schedule); a gather of the wrong size, a bad a_row or a non-supernodal factor
// is refused.
TEST(SparseCholesky, GatheredSolveEqualsTheReorderedOne) {
  const auto A = grid_laplacian(40, 1e-2);
  const Eigen::Index n = A.rows();
  std::vector<int> a_row(static_cast<size_t>(n));
  for (Eigen::Index r = 0; r < n; ++r) a_row[static_cast<size_t>(r)] = static_cast<int>((r * 7 + 3) % n);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
  for (const int threads : {1, 2}) {
    iarap::set_thread_count(threads);
    SparseCholesky chol(A);
    ASSERT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
    Eigen::MatrixXd B_a(n, 3), X_a, expected(n, 3);
    for (Eigen::Index r = 0; r < n; ++r) B_a.row(a_row[static_cast<size_t>(r)]) = B.row(r);
    chol.solve(B_a, X_a);
    for (Eigen::Index r = 0; r < n; ++r) expected.row(r) = X_a.row(a_row[static_cast<size_t>(r)]);
    const std::vector<int> gather = chol.gather_rows(a_row);
    ASSERT_EQ(gather.size(), static_cast<size_t>(n));
    Eigen::MatrixXd X, in_place = B;
    chol.solve_gathered(B, X, gather);
    EXPECT_EQ(X, expected) << threads << " threads";
    chol.solve_gathered(in_place, in_place, gather);
    EXPECT_EQ(in_place, expected) << threads << " threads";
    EXPECT_THROW(chol.solve_gathered(B, X, std::vector<int>(5, 0)), iarap::SolverError);
    std::vector<int> twice = a_row;
    twice[1] = twice[0];
    EXPECT_THROW(chol.gather_rows(twice), iarap::SolverError);
    EXPECT_THROW(chol.gather_rows(std::vector<int>(3, 0)), iarap::SolverError);
    // Freed workspaces are made again by the next solve: the same bits.
    chol.release_solve_workspaces();
    chol.solve_gathered(B, X, gather);
    EXPECT_EQ(X, expected) << threads << " threads";
  }
  iarap::set_thread_count(0);
  // The LDL^T fallback has no supernodal gather: empty, and solve_gathered refuses.
  SparseCholesky ldlt(path_laplacian(30, -1.0 + 1e-3));
  ASSERT_EQ(ldlt.kind(), FactorizationKind::SimplicialLDLT);
  std::vector<int> identity(30);
  for (int r = 0; r < 30; ++r) identity[static_cast<size_t>(r)] = r;
  EXPECT_TRUE(ldlt.gather_rows(identity).empty());
  Eigen::MatrixXd X;
  EXPECT_THROW(ldlt.solve_gathered(Eigen::MatrixXd::Ones(30, 3), X, identity), iarap::SolverError);
}

TEST(SparseCholesky, IndefiniteFallsBackToLdlt) {
  // Eigenvalues of the path Laplacian lie in (0, 4); shifting by -1 makes it indefinite but nonsingular.
  const auto A = path_laplacian(50, -1.0 + 1e-3);
  const SparseCholesky chol(A);
  EXPECT_EQ(chol.kind(), FactorizationKind::SimplicialLDLT);
  EXPECT_EQ(iarap::factorization_name(chol.kind()), "simplicial-ldlt");
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(50, 3);
  EXPECT_LT(residual(A, chol.solve(B), B), 1e-8);
}

TEST(SparseCholesky, SingularThrows) {
  // Pure Neumann path Laplacian: constants are in the kernel.
  auto A = path_laplacian(20, 0.0);
  A.coeffRef(0, 0) = 1.0;
  A.coeffRef(19, 19) = 1.0;
  try {
    SparseCholesky chol(A);
    FAIL() << "expected SolverError, got " << iarap::factorization_name(chol.kind());
  } catch (const iarap::SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

TEST(SparseCholesky, NonFiniteAndMisuseThrow) {
  auto A = path_laplacian(5, 0.0);
  A.coeffRef(2, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SparseCholesky{A}, iarap::SolverError);
  const SparseCholesky empty;
  EXPECT_EQ(empty.kind(), FactorizationKind::None);
  EXPECT_THROW(empty.solve(Eigen::MatrixXd::Ones(5, 1)), iarap::SolverError);
  const SparseCholesky chol(path_laplacian(5, 0.0));
  EXPECT_THROW(chol.solve(Eigen::MatrixXd::Ones(4, 1)), iarap::SolverError);
  EXPECT_THROW(SparseCholesky{Eigen::SparseMatrix<double>(3, 4)}, iarap::SolverError);
}

TEST(SparseCholesky, EmptyMatrixSolvesToNoRows) {
  const SparseCholesky chol{Eigen::SparseMatrix<double>(0, 0)};
  EXPECT_EQ(chol.kind(), FactorizationKind::Empty);
  EXPECT_EQ(chol.solve(Eigen::MatrixXd(0, 3)).rows(), 0);
}

TEST(SparseCholesky, CopiesAreIndependentAndMovesKeepTheFactor) {
  const auto A = path_laplacian(30, 0.0);
  SparseCholesky a(A);
  const SparseCholesky b = a; // refactorizes
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(30, 2);
  const Eigen::MatrixXd X = a.solve(B);
  SparseCholesky c = std::move(a);
  EXPECT_LT((b.solve(B) - X).norm(), 1e-12 * X.norm());
  EXPECT_LT((c.solve(B) - X).norm(), 1e-12 * X.norm());
  EXPECT_EQ(b.kind(), FactorizationKind::CholmodSupernodalLLT);
}

} // namespace

namespace {

// analyze() on the pattern, then factorize() on values with that pattern, solves like a one-shot
// factorization; values on another pattern after analyze() are factorized from scratch, not wrongly.
TEST(SparseCholesky, AnalyzeThenFactorizeReusesOnlyTheSamePattern) {
  const auto A = path_laplacian(300, 0.0);
  Eigen::SparseMatrix<double> pattern = A;
  for (int k = 0; k < pattern.nonZeros(); ++k) pattern.valuePtr()[k] = 0.0;
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(300, 3);
  SparseCholesky chol;
  chol.analyze(pattern);
  EXPECT_EQ(chol.kind(), FactorizationKind::None);
  chol.factorize(A);
  EXPECT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
  EXPECT_LT(residual(A, chol.solve(B), B), 1e-12);

  const auto other = path_laplacian(200, 0.5);
  chol.analyze(pattern);
  chol.factorize(other);
  const Eigen::MatrixXd B2 = Eigen::MatrixXd::Random(200, 2);
  EXPECT_LT(residual(other, chol.solve(B2), B2), 1e-12);

  // Indefinite values on the analyzed pattern still fall back to LDL^T.
  const auto indefinite = path_laplacian(300, -1.0 + 1e-3);
  chol.analyze(pattern);
  chol.factorize(indefinite);
  EXPECT_EQ(chol.kind(), FactorizationKind::SimplicialLDLT);
  EXPECT_LT(residual(indefinite, chol.solve(B), B), 1e-9);
}

// New values on the pattern of the last LLT (soft weights, issue 32) refactorize numerically on the kept
// analysis: the result is that of a fresh factorization, bit for bit (same ordering, same arithmetic), and
// a matrix of another pattern or size still gets an analysis of its own.
TEST(SparseCholesky, RefactorizingNewValuesEqualsAFreshFactorization) {
  const auto A = path_laplacian(300, 0.0), A2 = path_laplacian(300, 0.7), other = path_laplacian(200, 0.1);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(300, 3);
  SparseCholesky chol(A);
  chol.factorize(A2);
  EXPECT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
  const SparseCholesky fresh(A2);
  EXPECT_EQ((chol.solve(B) - fresh.solve(B)).norm(), 0.0);
  chol.factorize(other);
  const Eigen::MatrixXd B2 = Eigen::MatrixXd::Random(200, 2);
  EXPECT_LT(residual(other, chol.solve(B2), B2), 1e-12);
}

// CHOLMOD's own OpenMP teams are serialized below 4 allowed threads (sparse_cholesky.cpp): the caller's
// OpenMP settings come back unchanged, and the factor is the same with or without its teams (bit for bit with
// a single-threaded BLAS; CHOLMOD's serial solve shows it; the project's solve splits differently with the
// thread count).
TEST(SparseCholesky, CholmodTeamsLeaveTheCallersSettingsAlone) {
  const int n = 60; // a 2D grid Laplacian: supernodes large enough for CHOLMOD's parallel loops
  const Eigen::SparseMatrix<double> A = iarap::test::grid_laplacian(n, 0.01);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n * n, 3);
  const int threads = iarap::thread_count(), levels = omp_get_max_active_levels();
  omp_set_max_active_levels(3);
  Eigen::MatrixXd X[2];
  const int counts[2] = {1, 4};
  for (int k = 0; k < 2; ++k) {
    iarap::set_thread_count(counts[k]);
    SparseCholesky chol;
    chol.analyze(A);
    chol.factorize(A);
    EXPECT_EQ(omp_get_max_active_levels(), 3) << counts[k] << " threads";
    EXPECT_EQ(iarap::thread_count(), counts[k]);
    ASSERT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
    chol.solve_with_cholmod(B, X[k]);
    EXPECT_LT(residual(A, X[k], B), 1e-12);
  }
  // The same ordering and supernodes; OpenBLAS (when it is the BLAS) splits its kernels by the thread count
  // SparseCholesky allows it (1 against 4 here), which changes the rounding only. cond(A) <= 8 / 0.01.
  EXPECT_LT((X[0] - X[1]).norm() / X[0].norm(), 1e-13);
  omp_set_max_active_levels(levels);
  iarap::set_thread_count(threads);
}

} // namespace

// Both orderings reach CHOLMOD (their factors differ in size) and solve to rounding; copies, analyze() and a
// refactorization keep the chosen one.
TEST(SparseCholesky, FillOrderingIsTheCallersChoice) {
  const auto A = grid_laplacian(60, 1e-3);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
  std::size_t bytes[2] = {0, 0};
  for (const auto ordering : {iarap::FillOrdering::Amd, iarap::FillOrdering::Metis}) {
    SparseCholesky chol;
    chol.set_ordering(ordering);
    chol.analyze(A);
    chol.factorize(A);
    ASSERT_EQ(chol.kind(), FactorizationKind::CholmodSupernodalLLT);
    EXPECT_EQ(chol.ordering(), ordering);
    EXPECT_EQ(chol.used_ordering(), ordering);
    // cond(A) <= 8 / 1e-3: a backward-stable Cholesky leaves a relative residual of a few machine epsilons.
    EXPECT_LT(residual(A, chol.solve(B), B), 1e-12) << iarap::fill_ordering_name(ordering);
    bytes[ordering == iarap::FillOrdering::Metis] = chol.factor_bytes();
    const SparseCholesky copy(chol);
    EXPECT_EQ(copy.ordering(), ordering);
    EXPECT_EQ(copy.factor_bytes(), chol.factor_bytes());
    chol.factorize(A * 2.0); // same pattern: numeric refactorization, same factor size
    EXPECT_EQ(chol.ordering(), ordering);
    EXPECT_EQ(chol.factor_bytes(), bytes[ordering == iarap::FillOrdering::Metis]);
  }
  EXPECT_NE(bytes[0], bytes[1]);
  // Auto: AMD below a million rows (this matrix), METIS from there.
  SparseCholesky automatic(A);
  EXPECT_EQ(automatic.ordering(), iarap::FillOrdering::Auto);
  EXPECT_EQ(automatic.used_ordering(), iarap::FillOrdering::Amd);
  EXPECT_EQ(automatic.factor_bytes(), bytes[0]);
  EXPECT_EQ(iarap::resolved_ordering(iarap::FillOrdering::Auto, iarap::auto_metis_rows - 1),
            iarap::FillOrdering::Amd);
  EXPECT_EQ(iarap::resolved_ordering(iarap::FillOrdering::Auto, iarap::auto_metis_rows),
            iarap::FillOrdering::Metis);
  EXPECT_EQ(iarap::resolved_ordering(iarap::FillOrdering::Amd, iarap::auto_metis_rows),
            iarap::FillOrdering::Amd);
  EXPECT_EQ(iarap::parse_fill_ordering("metis"), iarap::FillOrdering::Metis);
  EXPECT_EQ(iarap::fill_ordering_name(iarap::parse_fill_ordering("amd")), "amd");
  EXPECT_EQ(iarap::fill_ordering_name(iarap::parse_fill_ordering("auto")), "auto");
  EXPECT_THROW(iarap::parse_fill_ordering("nesdis"), iarap::InputError);
}
