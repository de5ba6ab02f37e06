#include "lbfgs_direction.h"

#include "inner.h"

#include <algorithm>
#include <cmath>

namespace iarap::detail {

LbfgsDirection::LbfgsDirection(int window)
    : window_(window), s_(static_cast<size_t>(window)), y_(static_cast<size_t>(window)),
      rho_(static_cast<size_t>(window)) {}

bool LbfgsDirection::push(const Eigen::MatrixXd& x_next, const Eigen::MatrixXd& x,
                          const Eigen::MatrixXd& g_next, const Eigen::MatrixXd& g) {
  spare_s_.resize(x.rows(), x.cols());
  spare_y_.resize(g.rows(), g.cols());
  const Eigen::Index n = x.size();
  const double *xn = x_next.data(), *xo = x.data(), *gn = g_next.data(), *go = g.data();
  double *ps = spare_s_.data(), *py = spare_y_.data();
  double sy = 0, ss = 0, yy = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double si = xn[i] - xo[i], yi = gn[i] - go[i];
    ps[i] = si;
    py[i] = yi;
    sy += si * yi;
    ss += si * si;
    yy += yi * yi;
  }
  // Relative threshold: a pair whose curvature is rounding-level against |s| |y| carries no information.
  if (!(sy > 1e-12 * std::sqrt(ss) * std::sqrt(yy))) return false;
  newest_ = (newest_ + 1) % window_;
  const auto slot = static_cast<size_t>(newest_);
  s_[slot].swap(spare_s_);
  y_[slot].swap(spare_y_);
  rho_[slot] = 1.0 / sy;
  pairs_ = std::min(pairs_ + 1, window_);
  return true;
}

void LbfgsDirection::newest_to_oldest(Eigen::MatrixXd& q, std::vector<double>& alpha) const {
  for (int a = 0; a < pairs_; ++a) {
    const auto slot = static_cast<size_t>((newest_ - a + window_) % window_);
    alpha[static_cast<size_t>(a)] = rho_[slot] * inner(s_[slot], q);
    q -= alpha[static_cast<size_t>(a)] * y_[slot];
  }
}

void LbfgsDirection::oldest_to_newest(const std::vector<double>& alpha, Eigen::MatrixXd& r) const {
  for (int a = pairs_ - 1; a >= 0; --a) {
    const auto slot = static_cast<size_t>((newest_ - a + window_) % window_);
    const double beta = rho_[slot] * inner(y_[slot], r);
    r += (alpha[static_cast<size_t>(a)] - beta) * s_[slot];
  }
  r *= -1.0; // in place: no temporary
}

} // namespace iarap::detail
