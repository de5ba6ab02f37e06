#include "injectivity_barrier.h"

#include "iarap/param/injective_step.h"

#include "uv_elastic_energy.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iarap::param_detail {
namespace {

Eigen::Matrix2d row_matrix(const Eigen::MatrixXd& rows, Eigen::Index f) {
  Eigen::Matrix2d M;
  M << rows(f, 0), rows(f, 1), rows(f, 2), rows(f, 3);
  return M;
}

double det(const Eigen::MatrixXd& J, Eigen::Index f) {
  return J(f, 0) * J(f, 3) - J(f, 1) * J(f, 2);
}

// d det / dJ = the cofactor matrix (J11, -J10; -J01, J00), row by row; linear in J.
Eigen::RowVector4d cofactor(const Eigen::MatrixXd& J, Eigen::Index f) {
  return Eigen::RowVector4d(J(f, 3), -J(f, 2), -J(f, 1), J(f, 0));
}

} // namespace

InjectivityBarrier::InjectivityBarrier(const DiskMesh& disk, double weight, double threshold,
                                       double step_fraction, const Eigen::MatrixXd& J0)
    : disk_(disk), weight_(weight), threshold_(threshold), step_fraction_(step_fraction),
      exempt_(static_cast<std::size_t>(J0.rows()), 0) {
  for (Eigen::Index f = 0; f < J0.rows(); ++f) exempt_[static_cast<std::size_t>(f)] = !(det(J0, f) > 0);
}

double InjectivityBarrier::value(const Eigen::MatrixXd& J) const {
  double total = 0;
  for (Eigen::Index f = 0; f < J.rows(); ++f) {
    const double x = det(J, f);
    if (exempt_[static_cast<std::size_t>(f)] || x >= threshold_) continue;
    if (!(x > 0)) return std::numeric_limits<double>::infinity();
    total += disk_.frames.area(f) * (-std::log(x / threshold_) + x / threshold_ - 1);
  }
  return weight_ * total;
}

// psi'(x) = 1 / eps - 1 / x; the gradient in J is area mu psi'(det J) cof J.
void InjectivityBarrier::add_gradient(const Eigen::MatrixXd& J, Eigen::MatrixXd& grad) const {
  A_.setZero(J.rows(), 4);
  for (Eigen::Index f = 0; f < J.rows(); ++f) {
    const double x = det(J, f);
    if (exempt_[static_cast<std::size_t>(f)] || x >= threshold_ || !(x > 0)) continue;
    A_.row(f) = (weight_ * disk_.frames.area(f) * (1 / threshold_ - 1 / x)) * cofactor(J, f);
  }
  scatter_face_matrices(disk_, A_, nullptr, grad);
}

// d/dJ [area mu psi'(det J) cof J] [dJ] = area mu (psi''(det J) (cof J : dJ) cof J + psi'(det J) cof dJ),
// psi''(x) = 1 / x^2.
void InjectivityBarrier::add_hessian_product(const Eigen::MatrixXd& J, const Eigen::MatrixXd& dJ,
                                             Eigen::MatrixXd& out) const {
  A_.setZero(J.rows(), 4);
  for (Eigen::Index f = 0; f < J.rows(); ++f) {
    const double x = det(J, f);
    if (exempt_[static_cast<std::size_t>(f)] || x >= threshold_ || !(x > 0)) continue;
    const Eigen::RowVector4d cof = cofactor(J, f);
    const double a = weight_ * disk_.frames.area(f);
    A_.row(f) = a * ((cof.dot(dJ.row(f)) / (x * x)) * cof + (1 / threshold_ - 1 / x) * cofactor(dJ, f));
  }
  scatter_face_matrices(disk_, A_, nullptr, out);
}

double InjectivityBarrier::step_limit(const Eigen::MatrixXd& J, const Eigen::MatrixXd& dJ) const {
  double t = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < J.rows(); ++f)
    if (!exempt_[static_cast<std::size_t>(f)])
      t = std::min(t, first_degenerate_step(row_matrix(J, f), row_matrix(J, f) + row_matrix(dJ, f)));
  return step_fraction_ * t;
}

} // namespace iarap::param_detail
