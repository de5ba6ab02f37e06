#include "anderson_acceleration.h"

#include <Eigen/QR>

#include <algorithm>

namespace iarap::detail {

AndersonAcceleration::AndersonAcceleration(int window, Eigen::Index size)
    : window_(window), size_(size), dF_(size, window), dG_(size, window), gram_(window, window),
      dF_f_(window), f_prev_(size), G_prev_(size), f_(size), df_(size) {}

void AndersonAcceleration::reset() {
  columns_ = 0;
  newest_ = -1;
  has_previous_ = false;
}

bool AndersonAcceleration::step(const double* x, const double* Gx, double* next) {
  const Eigen::Map<const Eigen::VectorXd> xk(x, size_), G(Gx, size_);
  Eigen::Map<Eigen::VectorXd> out(next, size_);
  f_ = G - xk;
  if (has_previous_) {
    df_ = f_ - f_prev_;
    const double norm = df_.norm();
    if (norm > 0.0) { // a zero difference (x_k repeated) carries no information
      // Scaled to unit length so that the normal equations below stay well conditioned (Peng et al.).
      const int j = (newest_ + 1) % window_; // the oldest column once the window is full
      dF_.col(j) = df_ / norm;
      dG_.col(j) = (G - G_prev_) / norm;
      newest_ = j;
      columns_ = std::min(columns_ + 1, window_);
      // The new Gram column in one pass over dF (columns are used in storage order: the least-squares
      // problem does not depend on the order of its columns).
      gram_.col(j).head(columns_).noalias() = dF_.leftCols(columns_).transpose() * dF_.col(j);
      gram_.row(j).head(columns_) = gram_.col(j).head(columns_).transpose();
      // dF_c . f_k = dF_c . f_{k-1} + dF_c . (norm dF_j) for the columns kept: the right-hand side follows
      // from the Gram column without another pass over dF; only the new column needs its own product.
      for (int c = 0; c < columns_; ++c)
        if (c != j) dF_f_(c) += norm * gram_(c, j);
      dF_f_(j) = dF_.col(j).dot(f_);
    }
  }
  f_prev_ = f_;
  G_prev_ = G;
  has_previous_ = true;
  if (columns_ == 0) {
    out = G;
    return false;
  }
  // theta = argmin ||f - dF theta|| through the m x m normal equations; the complete orthogonal
  // decomposition gives the minimum-norm theta when two differences are (nearly) parallel.
  const Eigen::VectorXd theta =
      gram_.topLeftCorner(columns_, columns_).completeOrthogonalDecomposition().solve(dF_f_.head(columns_));
  out.noalias() = G - dG_.leftCols(columns_) * theta; // one pass over dG
  return true;
}

} // namespace iarap::detail
