// Internal: a symmetric positive semi-definite system with some unknowns held at given values,
// A_ff x_f = b_f - A_fc x_c, factorized once and solved for as many right-hand sides as needed. The one
// linear solve of the param module: LSCM (two pinned vertices), the fixed-boundary maps and the ARAP
// global step all reduce to it.
#pragma once
#include "iarap/solver/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace iarap::param_detail {

class ConstrainedSystem {
public:
  // A: n x n, symmetric; fixed: distinct indices in 0..n-1. Factorizes A_ff (SparseCholesky); throws
  // SolverError when it is singular. `what` names the system in that message ("the LSCM system").
  ConstrainedSystem(const Eigen::SparseMatrix<double>& A, const std::vector<int>& fixed, const char* what);

  // Solves for the free rows of x (n x k) given its fixed rows and b (n x k); the fixed rows of x are kept.
  void solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x);
  // A_ff^{-1} r for r #free x k in the order of free() (an iteration on the free unknowns alone).
  Eigen::MatrixXd solve_free(const Eigen::MatrixXd& r) const { return cholesky_.solve(r); }
  // The free unknowns, increasing.
  const std::vector<int>& free() const { return free_; }
  FactorizationKind kind() const { return cholesky_.kind(); }

private:
  std::vector<int> free_;            // the free unknowns in order
  std::vector<int> fixed_;           // the fixed ones
  Eigen::SparseMatrix<double> A_fc_; // #free x #fixed
  SparseCholesky cholesky_;
  Eigen::MatrixXd rhs_, solution_, fixed_values_; // workspaces reused from solve to solve
};

} // namespace iarap::param_detail
