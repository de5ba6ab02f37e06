// Factorization of a sparse symmetric system matrix, reused for many right-hand sides (the ARAP global step).
#pragma once
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace iarap {

// Which factorization a SparseCholesky ended up with.
enum class FactorizationKind {
  None,                 // nothing factorized yet
  Empty,                // a 0 x 0 matrix (e.g. every vertex constrained): solves return 0 rows
  CholmodSupernodalLLT, // CHOLMOD supernodal Cholesky: the matrix is positive definite
  SimplicialLDLT,       // Eigen's LDL^T: the fallback for symmetric matrices that are not positive definite
  SimplicialLLT, // Eigen's simplicial Cholesky (AMD ordering): positive definite, below simplicial_below()
};

// "none", "empty", "cholmod-supernodal-llt", "simplicial-ldlt", "simplicial-llt".
std::string factorization_name(FactorizationKind kind);

// CHOLMOD's fill-reducing ordering (the symbolic analysis), one ordering per analysis. Amd: the faster
// analysis. Metis: nested dissection, a factor with 25-40% fewer entries on large surface meshes (less
// memory, a faster numeric factorization and solve) for an analysis about 4x as long. Auto: AMD below
// auto_metis_rows rows, METIS from there, the choice CHOLMOD's default makes on the armadillo family (AMD
// at 622K free rows, METIS at 2.49M) without its cost of running both orderings (docs/performance.md).
enum class FillOrdering { Auto, Amd, Metis };
constexpr long auto_metis_rows = 1000000;

// The ordering Auto stands for on an n x n matrix; Amd and Metis stand for themselves.
FillOrdering resolved_ordering(FillOrdering ordering, long n);

// "auto" | "amd" | "metis"; anything else throws InputError naming the value and the choices.
FillOrdering parse_fill_ordering(const std::string& name);
std::string fill_ordering_name(FillOrdering ordering);

// Owns the factorization of a symmetric matrix A (only its lower triangle is read). CHOLMOD stays
// behind a pimpl so that no public header includes SuiteSparse. A value type: copying refactorizes the
// stored matrix, moving is cheap.
class SparseCholesky {
public:
  SparseCholesky();
  // Factorizes A; see factorize().
  explicit SparseCholesky(const Eigen::SparseMatrix<double>& A);
  SparseCholesky(const SparseCholesky& other);
  SparseCholesky& operator=(const SparseCholesky& other);
  SparseCholesky(SparseCholesky&&) noexcept;
  SparseCholesky& operator=(SparseCholesky&&) noexcept;
  ~SparseCholesky();

  // The ordering of the next analysis (analyze, or a factorize that is not a refactorization); kept by
  // copies. Default FillOrdering::Auto. used_ordering(): what the last analysis ran (Amd or Metis; the
  // requested ordering resolved for rows() before any).
  void set_ordering(FillOrdering ordering);
  FillOrdering ordering() const;
  FillOrdering used_ordering() const;

  // Matrices of fewer rows than this are factorized by Eigen's simplicial LLT (its own AMD ordering, no
  // supernodes) instead of CHOLMOD, whose analysis (ordering, transposes, elimination tree, supernodal
  // symbolic) costs more than the whole factorization of a system of a few hundred rows: an atlas
  // factorizes two per chart. Default 0 (always CHOLMOD); kept by copies.
  void set_simplicial_below(Eigen::Index rows);
  Eigen::Index simplicial_below() const;

  // The symbolic half of factorize (CHOLMOD's fill-reducing ordering and supernodal analysis) on the
  // pattern of the square, compressed matrix `pattern` (values ignored). Forgets any factorization.
  // Independent of the values, so it may run (on another thread) while they are being computed.
  void analyze(const Eigen::SparseMatrix<double>& pattern);

  // Factorizes the n x n symmetric A: below simplicial_below() rows Eigen's simplicial LLT; else CHOLMOD's
  // supernodal LLT, reusing the symbolic analysis when A is compressed with exactly the analyzed pattern
  // (analyze()'s, or the last successful LLT's matrix's: a refactorization is numeric only); if A is not
  // positive definite, Eigen's SimplicialLDLT.
  // Throws SolverError when A is not square, has non-finite entries, or both factorizations fail (a zero
  // or numerically zero pivot: A is singular); the object is then empty.
  void factorize(const Eigen::SparseMatrix<double>& A);

  // X with A X = B for B n x k (all columns in one call). Throws SolverError when nothing is factorized
  // or B has the wrong number of rows.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // The same X, written into X (resized only when its shape changes; X may be B itself, solved in place
  // without a second n x k array). For the CHOLMOD factorization the
  // solve's workspaces live in this object and are reused from call to call: repeated solves of one shape
  // allocate nothing. Not for concurrent use on one object (hence non-const).
  //
  // Both solves run the project's own supernodal triangular solves over CHOLMOD's factor
  // (src/solver/supernodal_solve.h): the k columns together, split over thread_count() threads by
  // subtrees of the elimination tree. The result is deterministic for a given thread count and differs
  // between thread counts by rounding only; the two solves agree bit for bit at one thread count (also
  // when called inside a parallel region, where the calling thread does all the work).
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X);
  // For B and X whose row r is A's row a_row[r] (a permutation of A's rows), the supernodal solve can gather
  // B's rows straight into the factor's order instead of through a reordered copy of B: one n x k array
  // less at a solve's peak (issue 44). gather_rows(a_row) is that order (for each row of the factor, its
  // row of B), valid until the next analysis; empty when the factorization is not CHOLMOD's supernodal one
  // (then reorder B by hand and call solve). solve_gathered(B, X, gather) is solve() for B and X in
  // a_row's order, bit for bit the reordered solve's X; X may be B. Throws SolverError on a gather of the
  // wrong size or without a supernodal factorization.
  std::vector<int> gather_rows(const std::vector<int>& a_row) const;
  void solve_gathered(const Eigen::MatrixXd& B, Eigen::MatrixXd& X, const std::vector<int>& gather);
  // The same X by CHOLMOD's own solve (cholmod_solve2, serial, workspaces reused like solve's): the
  // reference the hand-written solve is measured and tested against. The LDL^T fallback solves as solve().
  void solve_with_cholmod(const Eigen::MatrixXd& B, Eigen::MatrixXd& X);

  // Frees the workspaces the solves keep between calls (CHOLMOD's and the supernodal solve's; the next
  // solve makes them again): a caller done with one kind of solve, such as `iarap bench` after timing
  // cholmod_solve2 beside its own, does not hold them through the rest of its run.
  void release_solve_workspaces();

  FactorizationKind kind() const;
  Eigen::Index rows() const;

  // Bytes held: the factor (CHOLMOD's supernodal L with its permutation and column structure, or the LDL^T
  // fallback's L and D) and its solve plan; the copies of the factorized matrix and of the analyzed
  // pattern kept for refactorization.
  std::size_t factor_bytes() const;
  std::size_t kept_matrix_bytes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace iarap
