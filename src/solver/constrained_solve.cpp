#include "constrained_solve.h"

#include "iarap/core/errors.h"

#include <string>

namespace iarap::detail {

namespace {

// A_ff, and A_fc when asked, of A in compressed form (split_system reads the compressed arrays).
void split(const Eigen::SparseMatrix<double>& A, const ConstraintLayout& layout,
           Eigen::SparseMatrix<double>& A_ff, Eigen::SparseMatrix<double>* A_fc) {
  if (A.isCompressed()) return split_system(A, layout, A_ff, A_fc);
  Eigen::SparseMatrix<double> compressed = A;
  compressed.makeCompressed();
  split_system(compressed, layout, A_ff, A_fc);
}

SparseCholesky factorize_named(const Eigen::SparseMatrix<double>& A_ff, const char* what) {
  SparseCholesky cholesky;
  cholesky.set_simplicial_below(simplicial_free_rows);
  try {
    cholesky.factorize(A_ff);
  } catch (const SolverError& e) {
    throw SolverError(std::string(what) + " (" + std::to_string(A_ff.rows()) +
                      " free unknowns) cannot be factorized: " + e.what());
  }
  return cholesky;
}

} // namespace

SparseCholesky factorize_free(const Eigen::SparseMatrix<double>& A, const ConstraintLayout& layout,
                              const char* what) {
  Eigen::SparseMatrix<double> A_ff;
  split(A, layout, A_ff, nullptr);
  return factorize_named(A_ff, what);
}

void solve_constrained(const Eigen::SparseMatrix<double>& A, const std::vector<int>& constrained,
                       const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const char* what) {
  const ConstraintLayout layout = constraint_layout(A.rows(), constrained);
  Eigen::SparseMatrix<double> A_ff, A_fc;
  split(A, layout, A_ff, &A_fc);
  SparseCholesky cholesky = factorize_named(A_ff, what);
  const auto k = b.cols();
  Eigen::MatrixXd x_c(static_cast<Eigen::Index>(constrained.size()), k);
  for (std::size_t p = 0; p < constrained.size(); ++p)
    x_c.row(static_cast<Eigen::Index>(p)) = x.row(constrained[p]);
  Eigen::MatrixXd rhs(static_cast<Eigen::Index>(layout.free.size()), k), solution;
  for (std::size_t p = 0; p < layout.free.size(); ++p)
    rhs.row(static_cast<Eigen::Index>(p)) = b.row(layout.free[p]);
  if (!constrained.empty()) rhs.noalias() -= A_fc * x_c;
  cholesky.solve(rhs, solution);
  for (std::size_t p = 0; p < layout.free.size(); ++p)
    x.row(layout.free[p]) = solution.row(static_cast<Eigen::Index>(p));
}

} // namespace iarap::detail
