#include "iarap/solver/polar_rotation.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace iarap {

namespace {

// X^{-T} * det(X): column i is the cross product of the other two columns.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& X) {
  Eigen::Matrix3d C;
  C.col(0) = X.col(1).cross(X.col(2));
  C.col(1) = X.col(2).cross(X.col(0));
  C.col(2) = X.col(0).cross(X.col(1));
  return C;
}

// Newton (with the refinement below) stays accurate to ~1e-15 / sigma_2 down to sigma_3 / sigma_2 ~ 1e-14
// (measured); below det ~ 1e-10 |X|^3 the matrix is rank deficient up to rounding and the SVD decides
// which optimal rotation to return.
constexpr double kNewtonDeterminant = 1e-10;
// Quadratic convergence: the error after a step is about (step size)^2 / 2, so a step below 1e-8
// leaves an error at rounding level.
constexpr double kNewtonStep = 1e-8;
// Determinant scaling helps only far from convergence; near it, the plain step converges faster.
constexpr double kScalingOff = 1e-2;
constexpr int kNewtonMaxIterations = 30;
// The refinement corrects rounding-level errors only.
constexpr double kRefineMaxAngle = 1e-6;

// One Newton step on the rotation group: with H = R^T S = (I + [w]x) T and T symmetric,
// axial(H - H^T) = (tr(T) I - T) w. The 3x3 system has eigenvalues sigma_i + sigma_j, so it stays
// well conditioned when S is not, and brings R to rounding level even where the scaled Newton
// iteration (error ~ cond(S) * eps) did not; S symmetric positive definite then gives R = I to ~1e-16.
Eigen::Matrix3d refine_rotation(const Eigen::Matrix3d& R, const Eigen::Matrix3d& S) {
  const Eigen::Matrix3d H = R.transpose() * S;
  const Eigen::Vector3d a(H(2, 1) - H(1, 2), H(0, 2) - H(2, 0), H(1, 0) - H(0, 1));
  const Eigen::Matrix3d T = 0.5 * (H + H.transpose());
  const Eigen::Matrix3d G = T.trace() * Eigen::Matrix3d::Identity() - T;
  const Eigen::Vector3d w = G.inverse() * a;
  const double angle = w.norm();
  // A singular G (rank <= 1: the optimum is not unique) or a large step: nothing to refine.
  if (!(angle > 0.0) || !(angle < kRefineMaxAngle))
    return R;
  return R * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Matrix3d rotation_by_svd(const Eigen::Matrix3d& X) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(X, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  // Singular values are sorted decreasingly: flipping the last column costs the least (sigma_3).
  if (U.determinant() * V.determinant() < 0)
    U.col(2) = -U.col(2);
  return refine_rotation(U * V.transpose(), X);
}

} // namespace

Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& S) {
  if (!S.allFinite())
    return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Scaling by the largest entry (not the Frobenius norm) cannot underflow or overflow.
  const double scale = S.cwiseAbs().maxCoeff();
  if (scale == 0.0)
    return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S0 = S / scale;
  Eigen::Matrix3d X = S0;
  const double n = X.norm();
  Eigen::Matrix3d C = cofactor(X);
  double det = X.col(0).dot(C.col(0));
  // Exactly symmetric with positive leading minors (Sylvester): positive definite, polar factor exactly I.
  // The rest state of ARAP produces such covariances; iterating would only add rounding.
  if (X(0, 1) == X(1, 0) && X(0, 2) == X(2, 0) && X(1, 2) == X(2, 1) && X(0, 0) > 0 &&
      X(0, 0) * X(1, 1) - X(0, 1) * X(1, 0) > 0 && det > 0)
    return Eigen::Matrix3d::Identity();
  if (!(det > kNewtonDeterminant * n * n * n))
    return rotation_by_svd(X);

  // Scaled Newton iteration X <- (g X + (g X)^{-T}) / 2 (Higham 1986); det X stays positive.
  double step = 1.0;
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    const double g = step > kScalingOff ? 1.0 / std::cbrt(det) : 1.0;
    const Eigen::Matrix3d next = 0.5 * (g * X + C / (g * det));
    step = (next - X).norm();
    X = next;
    if (step < kNewtonStep)
      return refine_rotation(X, S0);
    C = cofactor(X);
    det = X.col(0).dot(C.col(0));
  }
  return rotation_by_svd(X); // not reached for det > 0; a safe answer all the same
}

} // namespace iarap
