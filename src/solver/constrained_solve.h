// A symmetric system solved at its free rows with the constrained rows held, A_ff x_f = b_f - A_fc x_c: the
// global step of arap_solve (Eq. 16) for a system that is not an ArapData's. The param module's LSCM,
// fixed-boundary maps and UV global step use it, on the solver's constraint layout and split. Internal.
#pragma once
#include "constraint_layout.h"

#include "iarap/solver/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace iarap::detail {

// Below this many free unknowns the systems here are factorized by a simplicial LLT instead of CHOLMOD's
// supernodal one (SparseCholesky::set_simplicial_below): an atlas's charts, most of tens to hundreds of
// vertices, each factorize an LSCM and a UV system, and CHOLMOD's analysis was most of their cost.
constexpr Eigen::Index simplicial_free_rows = 4000;

// The factorization of A_ff (A n x n, symmetric) for `layout`. Throws SolverError when A_ff is singular,
// naming the system by `what` ("the LSCM system") and its number of free unknowns.
SparseCholesky factorize_free(const Eigen::SparseMatrix<double>& A, const ConstraintLayout& layout,
                              const char* what);

// x (n x k): its free rows become A_ff^{-1} (b_f - A_fc x_c), its `constrained` rows (distinct, in
// 0..n-1, not checked) are kept. b: n x k. One factorization, thrown away after the solve.
void solve_constrained(const Eigen::SparseMatrix<double>& A, const std::vector<int>& constrained,
                       const Eigen::MatrixXd& b, Eigen::MatrixXd& x, const char* what);

} // namespace iarap::detail
