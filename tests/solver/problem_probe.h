// The energy and gradient of a Problem (src/solver/problem.h) at a point x: what the derivative tests compare
// with central differences.
#pragma once
#include "solver/problem.h"

#include <Eigen/Core>

namespace iarap::test {

// E(x): x set, the local step run.
inline double energy_at(detail::Problem& problem, const Eigen::MatrixXd& x) {
  problem.set_positions(x);
  return problem.local_step();
}

// g(x): the local step, then the right-hand side and gradient there.
inline Eigen::MatrixXd gradient_at(detail::Problem& problem, const Eigen::MatrixXd& x) {
  energy_at(problem, x);
  problem.assemble_rhs();
  return problem.gradient();
}

} // namespace iarap::test
