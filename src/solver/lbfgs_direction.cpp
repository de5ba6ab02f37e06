#include "lbfgs_direction.h"

#include "local_global_problem.h"

#include <algorithm>
#include <cmath>

namespace iarap::detail {

LbfgsDirection::LbfgsDirection(int window)
    : window_(window), s_(static_cast<size_t>(window)), y_(static_cast<size_t>(window)),
      rho_(static_cast<size_t>(window)) {}

bool LbfgsDirection::push(const Eigen::MatrixXd& s, const Eigen::MatrixXd& y) {
  const double sy = inner(s, y);
  // Relative threshold: a pair whose curvature is rounding-level against |s| |y| carries no information.
  if (!(sy > 1e-12 * s.norm() * y.norm()))
    return false;
  newest_ = (newest_ + 1) % window_;
  const auto slot = static_cast<size_t>(newest_);
  s_[slot] = s;
  y_[slot] = y;
  rho_[slot] = 1.0 / sy;
  pairs_ = std::min(pairs_ + 1, window_);
  return true;
}

Eigen::MatrixXd LbfgsDirection::direction(const Eigen::MatrixXd& g, const LocalGlobalProblem& problem) const {
  Eigen::MatrixXd q = g;
  std::vector<double> alpha(static_cast<size_t>(pairs_));
  for (int a = 0; a < pairs_; ++a) { // newest to oldest
    const auto slot = static_cast<size_t>((newest_ - a + window_) % window_);
    alpha[static_cast<size_t>(a)] = rho_[slot] * inner(s_[slot], q);
    q -= alpha[static_cast<size_t>(a)] * y_[slot];
  }
  Eigen::MatrixXd r = problem.solve(q); // H_0 q
  for (int a = pairs_ - 1; a >= 0; --a) { // oldest to newest
    const auto slot = static_cast<size_t>((newest_ - a + window_) % window_);
    const double beta = rho_[slot] * inner(y_[slot], r);
    r += (alpha[static_cast<size_t>(a)] - beta) * s_[slot];
  }
  return -r;
}

} // namespace iarap::detail
