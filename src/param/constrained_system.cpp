#include "constrained_system.h"

#include "iarap/core/errors.h"

#include <limits>
#include <string>

namespace iarap::param_detail {

ConstrainedSystem::ConstrainedSystem(const Eigen::SparseMatrix<double>& A, const std::vector<int>& fixed,
                                     const char* what)
    : fixed_(fixed) {
  const Eigen::Index n = A.rows();
  // slot[i]: position of unknown i among the free ones (>= 0) or among the fixed ones (-1 - position).
  constexpr int unassigned = std::numeric_limits<int>::max();
  std::vector<int> slot(static_cast<std::size_t>(n), unassigned);
  for (std::size_t p = 0; p < fixed_.size(); ++p)
    slot[static_cast<std::size_t>(fixed_[p])] = -1 - static_cast<int>(p);
  for (Eigen::Index i = 0; i < n; ++i)
    if (slot[static_cast<std::size_t>(i)] == unassigned) {
      slot[static_cast<std::size_t>(i)] = static_cast<int>(free_.size());
      free_.push_back(static_cast<int>(i));
    }
  std::vector<Eigen::Triplet<double>> ff, fc;
  ff.reserve(static_cast<std::size_t>(A.nonZeros()));
  for (int col = 0; col < A.outerSize(); ++col) {
    const int c = slot[static_cast<std::size_t>(col)];
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      const int r = slot[static_cast<std::size_t>(it.row())];
      if (r < 0) continue;
      if (c >= 0)
        ff.emplace_back(r, c, it.value());
      else
        fc.emplace_back(r, -1 - c, it.value());
    }
  }
  const auto nf = static_cast<Eigen::Index>(free_.size());
  Eigen::SparseMatrix<double> A_ff(nf, nf);
  A_ff.setFromTriplets(ff.begin(), ff.end());
  A_fc_.resize(nf, static_cast<Eigen::Index>(fixed_.size()));
  A_fc_.setFromTriplets(fc.begin(), fc.end());
  try {
    cholesky_.factorize(A_ff);
  } catch (const SolverError& e) {
    throw SolverError(std::string(what) + " (" + std::to_string(nf) +
                      " free unknowns) cannot be factorized: " + e.what());
  }
}

void ConstrainedSystem::solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) {
  const auto k = b.cols();
  fixed_values_.resize(static_cast<Eigen::Index>(fixed_.size()), k);
  for (std::size_t p = 0; p < fixed_.size(); ++p)
    fixed_values_.row(static_cast<Eigen::Index>(p)) = x.row(fixed_[p]);
  rhs_.resize(static_cast<Eigen::Index>(free_.size()), k);
  for (std::size_t p = 0; p < free_.size(); ++p) rhs_.row(static_cast<Eigen::Index>(p)) = b.row(free_[p]);
  if (!fixed_.empty()) rhs_.noalias() -= A_fc_ * fixed_values_;
  cholesky_.solve(rhs_, solution_);
  for (std::size_t p = 0; p < free_.size(); ++p)
    x.row(free_[p]) = solution_.row(static_cast<Eigen::Index>(p));
}

} // namespace iarap::param_detail
