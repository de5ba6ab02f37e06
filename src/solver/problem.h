// What the optimizers of the local/global engine see of a problem (plain, Anderson, L-BFGS, Newton, the
// line search and the stopping rules): an energy E(x) = min_R energy over the free unknowns x (#free x d,
// d = 3 for surfaces, 2 for UV maps) with its rotations fitted by the local step, its gradient g, the
// plain local/global iterate G(x), a preconditioner P^{-1} (the factorized system matrix) and Hessian
// products. Every problem keeps g = P (x - G(x)) for the plain step, so that P^{-1} is the initial inverse
// Hessian of L-BFGS and the trust-region norm of Newton. A problem whose unknowns must stay in a feasible
// set (injective UV maps) also bounds the steps of the line search (step_limit). Deformation
// (LocalGlobalProblem) and parameterization (src/param/uv_problem.h) are the two clients. Internal.
#pragma once
#include <Eigen/Core>

#include <limits>

namespace iarap::detail {

class Problem {
public:
  virtual ~Problem() = default;

  virtual Eigen::Index free_count() const = 0;
  // The columns of x, g and every direction: 3 (positions in space) or 2 (UV).
  virtual Eigen::Index dimension() const = 0;
  // x, the free unknowns; set_positions moves them (the local step at the new x is still to be done).
  virtual Eigen::MatrixXd positions() const = 0;
  virtual void set_positions(const Eigen::MatrixXd& x) = 0;

  // Local step at the current x: fits the rotations and returns the total energy there.
  virtual double local_step() = 0;
  // The right-hand side and the gradient at the point of the last local step.
  virtual void assemble_rhs() = 0;
  // The same right-hand side and the gradient's norm only, for the loops that read no more of g (plain,
  // Anderson): a problem may then leave g unstored (LocalGlobalProblem: one #free x 3 array less at a
  // solve's peak, issue 44); gradient() is then not to be read until the next assemble_rhs.
  virtual double assemble_rhs_gradient_norm() {
    assemble_rhs();
    return gradient().norm();
  }
  // The plain iterate from the point assemble_rhs last saw (never an energy increase); kept until the next
  // call.
  virtual const Eigen::MatrixXd& plain_step() = 0;
  // g at the point assemble_rhs last saw.
  virtual const Eigen::MatrixXd& gradient() const = 0;
  // P^{-1} r.
  virtual Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const = 0;

  // The Hessian of E at the point of the last local step: prepare, then products H v.
  virtual void prepare_hessian() = 0;
  virtual Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v) = 0;
  // A hint that prepare_hessian will follow most local steps (Newton): a problem may keep what it needs.
  virtual void keep_covariances() {}

  // The longest step t along d from x that the feasible set allows, already shortened by the problem's
  // safety fraction: a line search tries lengths up to min(1, step_limit). +infinity: no bound.
  virtual double step_limit(const Eigen::MatrixXd& /*x*/, const Eigen::MatrixXd& /*d*/) const {
    return std::numeric_limits<double>::infinity();
  }

  // Back-substitutions with the factorization so far.
  virtual int solves() const = 0;
};

} // namespace iarap::detail
