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

namespace {

// Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd: the largest of the four squares is taken
// first, so no division by a small number).
Eigen::Vector4d quaternion_of(const Eigen::Matrix3d& R) {
  const double t = R.trace();
  Eigen::Vector4d q;
  if (t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2)) {
    const double r = std::sqrt(1.0 + t);
    q << 0.5 * r, 0.5 * (R(2, 1) - R(1, 2)) / r, 0.5 * (R(0, 2) - R(2, 0)) / r, 0.5 * (R(1, 0) - R(0, 1)) / r;
  } else {
    int i = 0;
    if (R(1, 1) > R(i, i)) i = 1;
    if (R(2, 2) > R(i, i)) i = 2;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double r = std::sqrt(1.0 + R(i, i) - R(j, j) - R(k, k));
    q(0) = 0.5 * (R(k, j) - R(j, k)) / r;
    q(1 + i) = 0.5 * r;
    q(1 + j) = 0.5 * (R(j, i) + R(i, j)) / r;
    q(1 + k) = 0.5 * (R(k, i) + R(i, k)) / r;
  }
  return q;
}

// Newton on the rotation group from a nearby start converges quadratically: the error after a step is
// about (step size)^2 * |S| / (sigma_2 + sigma_3), so once a step is below 1e-8 the one taken leaves rounding.
constexpr double kGroupStep = 1e-8;
// A start this far (radians of the first step) is not near: the full iteration decides instead.
constexpr double kGroupFarStep = 0.5;
constexpr int kGroupMaxSteps = 6;
// G = tr(T) I - T must be safely positive definite (its eigenvalues are sigma_i + sigma_j at the optimum):
// its smallest leading-minor ratio against |G| below this and the step is not trusted.
constexpr double kGroupDefinite = 1e-6;

} // namespace

Eigen::Matrix3d polar_rotation_near(const Eigen::Matrix3d& S, const Eigen::Matrix3d& guess) {
  if (!S.allFinite() || !guess.allFinite())
    return polar_rotation(S);
  const double scale = S.cwiseAbs().maxCoeff();
  if (scale == 0.0)
    return Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S0 = S / scale;
  // The exact rest state (bitwise symmetric S) goes to polar_rotation, which returns exactly I when S is
  // positive definite. Nothing else does: a negative det S (a reflection, frequent with negative weights)
  // or a near rank deficiency have a unique optimal rotation whenever G below is safely positive definite
  // (its eigenvalues at the optimum are sigma_i + sigma_j with sigma_3 signed like det S), and Newton on the
  // rotation group finds it as it does for det S > 0; where G is not, polar_rotation's SVD decides.
  if (S0(0, 1) == S0(1, 0) && S0(0, 2) == S0(2, 0) && S0(1, 2) == S0(2, 1))
    return polar_rotation(S);
  Eigen::Vector4d start = quaternion_of(guess);
  const double start_norm = start.norm();
  if (!(start_norm > 0.5)) // not a rotation
    return polar_rotation(S);
  // Plain scalars from here: a step is ~150 flops, and Eigen's temporaries cost as much again.
  double qw = start(0) / start_norm, qx = start(1) / start_norm, qy = start(2) / start_norm, qz = start(3) / start_norm;
  double s[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s[i][j] = S0(i, j);
  double R[3][3];
  auto set_rotation = [&] {
    const double xx = qx * qx, yy = qy * qy, zz = qz * qz, xy = qx * qy, xz = qx * qz, yz = qy * qz;
    const double wx = qw * qx, wy = qw * qy, wz = qw * qz;
    R[0][0] = 1 - 2 * (yy + zz), R[0][1] = 2 * (xy - wz), R[0][2] = 2 * (xz + wy);
    R[1][0] = 2 * (xy + wz), R[1][1] = 1 - 2 * (xx + zz), R[1][2] = 2 * (yz - wx);
    R[2][0] = 2 * (xz - wy), R[2][1] = 2 * (yz + wx), R[2][2] = 1 - 2 * (xx + yy);
  };
  for (int step = 0; step < kGroupMaxSteps; ++step) {
    set_rotation();
    // H = R^T S0 = (I + [w]x) T to first order, T symmetric: axial(H - H^T) = (tr(T) I - T) w.
    double H[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H[i][j] = R[0][i] * s[0][j] + R[1][i] * s[1][j] + R[2][i] * s[2][j];
    const double a0 = H[2][1] - H[1][2], a1 = H[0][2] - H[2][0], a2 = H[1][0] - H[0][1];
    const double tr = H[0][0] + H[1][1] + H[2][2];
    const double g00 = tr - H[0][0], g11 = tr - H[1][1], g22 = tr - H[2][2];
    const double g01 = -0.5 * (H[0][1] + H[1][0]), g02 = -0.5 * (H[0][2] + H[2][0]), g12 = -0.5 * (H[1][2] + H[2][1]);
    // Adjugate of the symmetric G, and its determinant: w = adj(G) a / det(G).
    const double c00 = g11 * g22 - g12 * g12, c01 = g02 * g12 - g01 * g22, c02 = g01 * g12 - g02 * g11;
    const double c11 = g00 * g22 - g02 * g02, c12 = g01 * g02 - g00 * g12, c22 = g00 * g11 - g01 * g01;
    const double detG = g00 * c00 + g01 * c01 + g02 * c02;
    const double size = g00 + g11 + g22; // >= the largest eigenvalue of G when G is positive definite
    // Sylvester's criterion with margins: otherwise this is not the neighbourhood of the maximum.
    if (!(g00 > kGroupDefinite * size && c22 > kGroupDefinite * size * size &&
          detG > kGroupDefinite * size * size * size))
      return polar_rotation(S);
    const double inverse = 1.0 / detG;
    const double w0 = (c00 * a0 + c01 * a1 + c02 * a2) * inverse, w1 = (c01 * a0 + c11 * a1 + c12 * a2) * inverse,
                 w2 = (c02 * a0 + c12 * a1 + c22 * a2) * inverse;
    const double length2 = w0 * w0 + w1 * w1 + w2 * w2;
    if (step == 0 && !(length2 < kGroupFarStep * kGroupFarStep))
      return polar_rotation(S);
    // q <- q (1, w / 2): a rotation by 2 atan(|w| / 2) = |w| + O(|w|^3) about w, which keeps the
    // quadratic convergence; normalized so that q stays a unit quaternion.
    const double h0 = 0.5 * w0, h1 = 0.5 * w1, h2 = 0.5 * w2;
    const double nw = qw - qx * h0 - qy * h1 - qz * h2, nx = qx + qw * h0 + qy * h2 - qz * h1,
                 ny = qy + qw * h1 + qz * h0 - qx * h2, nz = qz + qw * h2 + qx * h1 - qy * h0;
    const double unit = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
    qw = nw * unit, qx = nx * unit, qy = ny * unit, qz = nz * unit;
    if (length2 < kGroupStep * kGroupStep) {
      set_rotation();
      Eigen::Matrix3d out;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out(i, j) = R[i][j];
      return out;
    }
  }
  return polar_rotation(S); // not converging from this start
}

} // namespace iarap
