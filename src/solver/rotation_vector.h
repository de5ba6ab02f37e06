// Rotation vectors (the exponential coordinates of SO(3)): the unknowns that stand for a rigid group's
// rotation (rigid_group_problem.h), R(w) = exp([w]x) R_0 about a fixed reference R_0. With theta = |w| and
// W = [w]x, exp(W) = I + (sin theta / theta) W + a W^2 (Rodrigues) and a small change dw turns R by
// exp([J(w) dw]x) to first order, J(w) = I + a W + b W^2 the left Jacobian, a = (1 - cos theta) / theta^2,
// b = (theta - sin theta) / theta^3 (their Taylor series below theta = 1e-2, where the closed forms cancel).
// J is invertible for theta < 2 pi. Internal to the solver.
#pragma once
#include <Eigen/Core>

namespace iarap::detail {

// [w]x, the cross-product matrix: [w]x v = w x v.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w);
// exp([w]x).
Eigen::Matrix3d rotation_of_vector(const Eigen::Vector3d& w);
// The rotation vector of R with |w| <= pi (the principal logarithm).
Eigen::Vector3d rotation_vector_of(const Eigen::Matrix3d& R);
// J(w), the left Jacobian: d exp([w]x) = [J(w) dw]x exp([w]x).
Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w);
// d (J(w)^T tau) / dw at a fixed tau: the part of the Hessian of f(exp([w]x) R_0) that comes from the
// curvature of the coordinates (tau the torque, the gradient in the turn J dw; zero at a minimum).
Eigen::Matrix3d left_jacobian_transpose_derivative(const Eigen::Vector3d& w, const Eigen::Vector3d& tau);

} // namespace iarap::detail
