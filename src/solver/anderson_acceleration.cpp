#include "anderson_acceleration.h"

#include <Eigen/QR>

#include <algorithm>

namespace iarap::detail {

AndersonAcceleration::AndersonAcceleration(int window, Eigen::Index size)
    : window_(window), size_(size), dF_(size, window), dG_(size, window), gram_(window, window),
      f_prev_(size), G_prev_(size), f_(size), df_(size) {}

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
      for (int i = 0; i < columns_; ++i) {
        const int c = (j - i + window_) % window_;
        gram_(j, c) = gram_(c, j) = dF_.col(j).dot(dF_.col(c));
      }
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
  Eigen::VectorXd rhs(columns_);
  Eigen::MatrixXd M(columns_, columns_);
  for (int a = 0; a < columns_; ++a) {
    const int ca = (newest_ - a + window_) % window_;
    rhs(a) = dF_.col(ca).dot(f_);
    for (int b = 0; b < columns_; ++b)
      M(a, b) = gram_(ca, (newest_ - b + window_) % window_);
  }
  const Eigen::VectorXd theta = M.completeOrthogonalDecomposition().solve(rhs);
  out = G;
  for (int a = 0; a < columns_; ++a)
    out.noalias() -= theta(a) * dG_.col((newest_ - a + window_) % window_);
  return true;
}

} // namespace iarap::detail
