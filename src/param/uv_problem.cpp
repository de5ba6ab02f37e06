#include "uv_problem.h"

#include "iarap/core/errors.h"
#include "iarap/param/triangle_frames.h"
#include "iarap/solver/closest_rotation_2d.h"

#include "../solver/constrained_solve.h"
#include "../solver/inner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace iarap::param_detail {
UvProblem::UvProblem(const DiskMesh& disk, std::unique_ptr<UvElasticEnergy> energy,
                     const std::vector<int>& pinned, std::optional<InjectivityBarrier> barrier,
                     Eigen::MatrixXd& U)
    : disk_(disk), energy_(std::move(energy)), barrier_(std::move(barrier)), U_(U),
      layout_(detail::constraint_layout(U.rows(), pinned)),
      cholesky_(detail::factorize_free(energy_->system(), layout_, "the ARAP parameterization system")) {}

Eigen::MatrixXd UvProblem::free_rows(const Eigen::MatrixXd& all) const {
  const std::vector<int>& free = layout_.free;
  Eigen::MatrixXd x(free_count(), 2);
  for (std::size_t p = 0; p < free.size(); ++p) x.row(static_cast<Eigen::Index>(p)) = all.row(free[p]);
  return x;
}

Eigen::MatrixXd UvProblem::full(const Eigen::MatrixXd& x) const {
  const std::vector<int>& free = layout_.free;
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(U_.rows(), 2);
  for (std::size_t p = 0; p < free.size(); ++p) all.row(free[p]) = x.row(static_cast<Eigen::Index>(p));
  return all;
}

Eigen::MatrixXd UvProblem::positions() const {
  return free_rows(U_);
}

void UvProblem::set_positions(const Eigen::MatrixXd& x) {
  // The plain step evaluates the map it returns, which the loops then set again: keep that evaluation.
  if (evaluated_ && x == positions()) return;
  const std::vector<int>& free = layout_.free;
  for (std::size_t p = 0; p < free.size(); ++p) U_.row(free[p]) = x.row(static_cast<Eigen::Index>(p));
  evaluated_ = false;
}

double UvProblem::local_step() {
  if (evaluated_) return W_;
  face_jacobians(disk_.frames, disk_.F, U_, J_);
  energy_->covariances(U_, J_, S_);
  R_.resize(S_.rows(), 4);
  for (Eigen::Index c = 0; c < S_.rows(); ++c) {
    Eigen::Matrix2d S;
    S << S_(c, 0), S_(c, 1), S_(c, 2), S_(c, 3);
    const Eigen::Matrix2d R = closest_rotation_2d(S);
    R_.row(c) << R(0, 0), R(0, 1), R(1, 0), R(1, 1);
  }
  E_ = energy_->energy(U_, J_, R_);
  W_ = E_ + (barrier_ ? barrier_->value(J_) : 0.0);
  evaluated_ = true;
  return W_;
}

void UvProblem::assemble_rhs() {
  Eigen::MatrixXd r;
  energy_->scatter(R_, r);
  Eigen::MatrixXd grad = 2.0 * (energy_->system() * U_ - r);
  if (barrier_) barrier_->add_gradient(J_, grad);
  g_ = free_rows(grad);
  x_rhs_ = positions();
  if (barrier_) J_rhs_ = J_;
  W_rhs_ = W_;
}

const Eigen::MatrixXd& UvProblem::plain_step() {
  constexpr double kArmijo = 1e-4;
  constexpr int kMaxHalvings = 40; // t down to 1e-12 of the bound: a step that short is no progress
  const Eigen::MatrixXd d = -solve(g_);
  if (!barrier_) {
    plain_ = x_rhs_ + d;
    return plain_;
  }
  const double slope = detail::inner(g_, d);
  double t = std::min(1.0, step_limit_from(J_rhs_, d));
  for (int halving = 0; halving < kMaxHalvings; ++halving, t *= 0.5) {
    plain_ = x_rhs_ + t * d;
    set_positions(plain_);
    if (local_step() <= W_rhs_ + kArmijo * t * slope) return plain_; // false for NaN and +inf
  }
  plain_ = x_rhs_; // no decrease found: stay (the energy rule then stops the solve)
  return plain_;
}

Eigen::MatrixXd UvProblem::solve(const Eigen::MatrixXd& r) const {
  ++solves_;
  return 0.5 * cholesky_.solve(r);
}

void UvProblem::prepare_hessian() {
  R_perp_.resize(R_.rows(), 4);
  inverse_norm_.resize(R_.rows());
  Eigen::VectorXd norm(R_.rows());
  for (Eigen::Index c = 0; c < S_.rows(); ++c) norm(c) = std::hypot(S_(c, 0) + S_(c, 3), S_(c, 2) - S_(c, 1));
  // A cell whose covariance vanishes is at the kink of -2 |S|_sim: its curvature is unbounded there, so it
  // is left out of the model (the trust region's energy check still sees it).
  const double floor = 1e-12 * (norm.size() > 0 ? norm.maxCoeff() : 0.0);
  for (Eigen::Index c = 0; c < R_.rows(); ++c) {
    // R = (cos, -sin; sin, cos) turned a quarter further: (-sin, -cos; cos, -sin).
    R_perp_.row(c) << R_(c, 1), -R_(c, 0), R_(c, 0), R_(c, 1);
    inverse_norm_(c) = norm(c) > floor ? 1 / norm(c) : 0.0;
  }
}

// E = const + tr(U^T M U) - 2 sum_c n_c with n_c = |(a_c, b_c)|, a = S00 + S11, b = S10 - S01 linear in U:
// the Hessian of n_c is w_c w_c^T / n_c with w_c = d/dU tr(R_perp_c^T S_c(U)), so that
// H v = 2 M v - 2 sum_c (tr(R_perp_c^T S_c(v)) / n_c) w_c, and the sum is the scatter of those multiples
// of R_perp_c (UvElasticEnergy::scatter is linear in its matrices).
Eigen::MatrixXd UvProblem::hessian_product(const Eigen::MatrixXd& v) {
  const Eigen::MatrixXd direction = full(v);
  Eigen::MatrixXd dJ, dS, h;
  face_jacobians(disk_.frames, disk_.F, direction, dJ);
  energy_->covariances(direction, dJ, dS);
  Eigen::MatrixXd A(R_perp_.rows(), 4);
  for (Eigen::Index c = 0; c < A.rows(); ++c)
    A.row(c) = (inverse_norm_(c) * R_perp_.row(c).dot(dS.row(c))) * R_perp_.row(c);
  energy_->scatter(A, h);
  Eigen::MatrixXd product = 2.0 * (energy_->system() * direction - h);
  if (barrier_) barrier_->add_hessian_product(J_, dJ, product);
  return free_rows(product);
}

double UvProblem::step_limit(const Eigen::MatrixXd& x, const Eigen::MatrixXd& d) const {
  if (!barrier_) return std::numeric_limits<double>::infinity();
  const std::vector<int>& free = layout_.free;
  Eigen::MatrixXd at = U_, J;
  for (std::size_t p = 0; p < free.size(); ++p) at.row(free[p]) = x.row(static_cast<Eigen::Index>(p));
  face_jacobians(disk_.frames, disk_.F, at, J);
  return step_limit_from(J, d);
}

double UvProblem::step_limit_from(const Eigen::MatrixXd& J, const Eigen::MatrixXd& d) const {
  Eigen::MatrixXd dJ;
  face_jacobians(disk_.frames, disk_.F, full(d), dJ);
  return barrier_->step_limit(J, dJ);
}

} // namespace iarap::param_detail
