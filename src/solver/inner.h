// sum_ij a_ij b_ij: the inner product of #free x 3 position-like matrices (positions, gradients, steps), as
// the optimizers of arap_solve take it. Internal to the solver.
#pragma once
#include <Eigen/Core>

namespace iarap::detail {

inline double inner(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.cwiseProduct(b).sum();
}

} // namespace iarap::detail
