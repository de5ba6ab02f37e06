// Norms of sparse matrices shared by the Laplacian tests: the largest entry and the largest diagonal
// entry (the scale every relative tolerance is measured against).
#pragma once
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace iarap::test {

inline double max_abs(const Eigen::SparseMatrix<double>& A) {
  double m = 0;
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

inline double max_abs_diagonal(const Eigen::SparseMatrix<double>& L) {
  return Eigen::VectorXd(L.diagonal()).cwiseAbs().maxCoeff();
}

} // namespace iarap::test
