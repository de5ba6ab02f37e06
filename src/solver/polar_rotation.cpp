#include "iarap/solver/polar_rotation.h"

#include "iarap/solver/closest_rotation_2d.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
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
  if (!(angle > 0.0) || !(angle < kRefineMaxAngle)) return R;
  return R * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

Eigen::Matrix3d rotation_by_svd(const Eigen::Matrix3d& X) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(X, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d& V = svd.matrixV();
  // Singular values are sorted decreasingly: flipping the last column costs the least (sigma_3).
  if (U.determinant() * V.determinant() < 0) U.col(2) = -U.col(2);
  return refine_rotation(U * V.transpose(), X);
}

} // namespace

Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& S) {
  if (!S.allFinite()) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  // Scaling by the largest entry (not the Frobenius norm) cannot underflow or overflow.
  const double scale = S.cwiseAbs().maxCoeff();
  if (scale == 0.0) return Eigen::Matrix3d::Identity();
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
  if (!(det > kNewtonDeterminant * n * n * n)) return rotation_by_svd(X);

  // Scaled Newton iteration X <- (g X + (g X)^{-T}) / 2 (Higham 1986); det X stays positive.
  double step = 1.0;
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    const double g = step > kScalingOff ? 1.0 / std::cbrt(det) : 1.0;
    const Eigen::Matrix3d next = 0.5 * (g * X + C / (g * det));
    step = (next - X).norm();
    X = next;
    if (step < kNewtonStep) return refine_rotation(X, S0);
    C = cofactor(X);
    det = X.col(0).dot(C.col(0));
  }
  return rotation_by_svd(X); // not reached for det > 0; a safe answer all the same
}

namespace {

// Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd: the largest of the four squares is taken
// first, so no division by a small number), not normalized: |q| = 1 to the rounding of R's orthonormality.
Eigen::Vector4d quaternion_of(const Eigen::Matrix3d& R) {
  const double t = R.trace();
  Eigen::Vector4d q;
  if (t >= R(0, 0) && t >= R(1, 1) && t >= R(2, 2)) {
    const double r = std::sqrt(1.0 + t), f = 0.5 / r;
    q << 0.5 * r, (R(2, 1) - R(1, 2)) * f, (R(0, 2) - R(2, 0)) * f, (R(1, 0) - R(0, 1)) * f;
  } else {
    int i = 0;
    if (R(1, 1) > R(i, i)) i = 1;
    if (R(2, 2) > R(i, i)) i = 2;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const double r = std::sqrt(1.0 + R(i, i) - R(j, j) - R(k, k)), f = 0.5 / r;
    q(0) = (R(k, j) - R(j, k)) * f;
    q(1 + i) = 0.5 * r;
    q(1 + j) = (R(j, i) + R(i, j)) * f;
    q(1 + k) = (R(k, i) + R(i, k)) * f;
  }
  return q;
}

// Newton on the rotation group from a nearby start converges quadratically: the error after a step is
// about (step size)^2 * |S| / (sigma_2 + sigma_3), so once a step is below 1e-8 the one taken leaves
// rounding.
constexpr double kGroupStep = 1e-8;
// A start this far (radians of the first step) is not near: the full iteration decides instead.
constexpr double kGroupFarStep = 0.5;
constexpr int kGroupMaxSteps = 6;
// G = tr(T) I - T must be safely positive definite (its eigenvalues are sigma_i + sigma_j at the optimum):
// its smallest leading-minor ratio against |G| below this and the step is not trusted.
constexpr double kGroupDefinite = 1e-6;

// The helpers from here on are inlined into both clones of the batched fit (a call would leave the
// AVX2 clone).
#define IARAP_INLINE_INTO_CLONES __attribute__((always_inline)) inline

// polar_rotation_near's start: S0 = S / (its largest entry), row-major, and the guess's unit quaternion.
// False when polar_rotation(S) decides instead: S = 0, the exact rest state (bitwise symmetric S, which
// polar_rotation turns into exactly I when S is positive definite) or a guess that is not a rotation. Nothing
// else goes there: a negative det S (a reflection, frequent with negative weights) or a near rank deficiency
// have a unique optimal rotation whenever G below is safely positive definite (its eigenvalues at the
// optimum are sigma_i + sigma_j with sigma_3 signed like det S), and Newton on the rotation group finds it
// as it does for det S > 0; where G is not, polar_rotation's SVD decides. Non-finite entries in S or the
// guess need no test here: they make the first step's concavity test fail (comparisons with NaN are false),
// and polar_rotation returns its non-finite answer. One reciprocal and multiplications, not a division
// per entry: this runs once per cell and iteration.
IARAP_INLINE_INTO_CLONES bool group_start(const Eigen::Matrix3d& S, const Eigen::Matrix3d& guess,
                                          double (&s)[9], double (&q)[4]) {
  double scale = 0.0;
  for (int k = 0; k < 9; ++k) scale = std::max(scale, std::abs(S(k)));
  if (scale == 0.0) return false;
  if (S(0, 1) == S(1, 0) && S(0, 2) == S(2, 0) && S(1, 2) == S(2, 1)) return false;
  const Eigen::Vector4d start = quaternion_of(guess);
  // Written out, not Eigen's squaredNorm: inside the AVX2 clone below Eigen could sum in another order,
  // and the two clones must agree to the bit.
  const double start_norm2 =
      start(0) * start(0) + start(1) * start(1) + start(2) * start(2) + start(3) * start(3);
  if (!(start_norm2 > 0.25)) // not a rotation
    return false;
  const double to_unit = 1.0 / std::sqrt(start_norm2), to_scaled = 1.0 / scale;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s[3 * i + j] = S(i, j) * to_scaled;
  for (int k = 0; k < 4; ++k) q[k] = start(k) * to_unit;
  return true;
}

// Four fits side by side, one per lane of a vector of doubles (GCC/Clang vector extension: one AVX
// register, or two SSE2 ones, or scalars where there is no SIMD). A Newton step is one long chain of
// dependent operations; four independent chains in lockstep fill the pipeline and the SIMD width.
// Vector arithmetic is IEEE arithmetic lane by lane, so each lane computes exactly what a fit on its own
// would.
constexpr int kLanes = 4;
typedef double Lanes __attribute__((vector_size(kLanes * sizeof(double))));
typedef long long LaneMask __attribute__((vector_size(kLanes * sizeof(long long))));

// R (row-major) of the unit quaternions q.
IARAP_INLINE_INTO_CLONES void rotation_of(const Lanes (&q)[4], Lanes (&R)[9]) {
  const Lanes qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const Lanes xx = qx * qx, yy = qy * qy, zz = qz * qz, xy = qx * qy, xz = qx * qz, yz = qy * qz;
  const Lanes wx = qw * qx, wy = qw * qy, wz = qw * qz;
  R[0] = 1 - 2 * (yy + zz), R[1] = 2 * (xy - wz), R[2] = 2 * (xz + wy);
  R[3] = 2 * (xy + wz), R[4] = 1 - 2 * (xx + zz), R[5] = 2 * (yz - wx);
  R[6] = 2 * (xz - wy), R[7] = 2 * (yz + wx), R[8] = 1 - 2 * (xx + yy);
}

// Newton on the rotation group for the lanes where `running` is set (scaled covariances s, row-major;
// unit quaternions q, updated in place). `converged` gets the lanes that converged; a lane that was running
// and did not (the model not safely concave, the first step too long, no convergence within the step limit)
// is for polar_rotation.
IARAP_INLINE_INTO_CLONES void group_newton(const Lanes (&s)[9], Lanes (&q)[4], LaneMask& running,
                                           LaneMask& converged) {
  converged = LaneMask{};
  for (int step = 0; step < kGroupMaxSteps; ++step) {
    bool any = false;
    for (int l = 0; l < kLanes; ++l) any |= running[l] != 0;
    if (!any) break;
    Lanes R[9];
    rotation_of(q, R);
    // H = R^T S0 = (I + [w]x) T to first order, T symmetric: axial(H - H^T) = (tr(T) I - T) w.
    Lanes H[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H[i][j] = R[i] * s[j] + R[3 + i] * s[3 + j] + R[6 + i] * s[6 + j];
    const Lanes a0 = H[2][1] - H[1][2], a1 = H[0][2] - H[2][0], a2 = H[1][0] - H[0][1];
    const Lanes tr = H[0][0] + H[1][1] + H[2][2];
    const Lanes g00 = tr - H[0][0], g11 = tr - H[1][1], g22 = tr - H[2][2];
    const Lanes g01 = -0.5 * (H[0][1] + H[1][0]), g02 = -0.5 * (H[0][2] + H[2][0]),
                g12 = -0.5 * (H[1][2] + H[2][1]);
    // Adjugate of the symmetric G, and its determinant: w = adj(G) a / det(G).
    const Lanes c00 = g11 * g22 - g12 * g12, c01 = g02 * g12 - g01 * g22, c02 = g01 * g12 - g02 * g11;
    const Lanes c11 = g00 * g22 - g02 * g02, c12 = g01 * g02 - g00 * g12, c22 = g00 * g11 - g01 * g01;
    const Lanes detG = g00 * c00 + g01 * c01 + g02 * c02;
    const Lanes size = g00 + g11 + g22; // >= the largest eigenvalue of G when G is positive definite
    // Sylvester's criterion with margins: otherwise this is not the neighbourhood of the maximum.
    const LaneMask concave = (g00 > kGroupDefinite * size) & (c22 > kGroupDefinite * size * size) &
                             (detG > kGroupDefinite * size * size * size);
    const Lanes inverse = 1.0 / detG;
    const Lanes w0 = (c00 * a0 + c01 * a1 + c02 * a2) * inverse,
                w1 = (c01 * a0 + c11 * a1 + c12 * a2) * inverse,
                w2 = (c02 * a0 + c12 * a1 + c22 * a2) * inverse;
    const Lanes length2 = w0 * w0 + w1 * w1 + w2 * w2;
    LaneMask take = running & concave;
    if (step == 0) take &= length2 < kGroupFarStep * kGroupFarStep;
    // q <- q (1, w / 2): a rotation by 2 atan(|w| / 2) = |w| + O(|w|^3) about w, which keeps the
    // quadratic convergence; normalized so that q stays a unit quaternion.
    const Lanes qw = q[0], qx = q[1], qy = q[2], qz = q[3];
    const Lanes h0 = 0.5 * w0, h1 = 0.5 * w1, h2 = 0.5 * w2;
    const Lanes nw = qw - qx * h0 - qy * h1 - qz * h2, nx = qx + qw * h0 + qy * h2 - qz * h1,
                ny = qy + qw * h1 + qz * h0 - qx * h2, nz = qz + qw * h2 + qx * h1 - qy * h0;
    const Lanes norm2 = nw * nw + nx * nx + ny * ny + nz * nz;
    Lanes unit;
    for (int l = 0; l < kLanes; ++l) unit[l] = 1.0 / std::sqrt(norm2[l]);
    q[0] = take ? nw * unit : qw;
    q[1] = take ? nx * unit : qx;
    q[2] = take ? ny * unit : qy;
    q[3] = take ? nz * unit : qz;
    const LaneMask done = take & (length2 < kGroupStep * kGroupStep);
    converged |= done;
    running = take & ~done;
  }
}

} // namespace

Eigen::Matrix3d polar_rotation_near(const Eigen::Matrix3d& S, const Eigen::Matrix3d& guess) {
  Eigen::Matrix3d R;
  polar_rotation_near(&S, &guess, &R, 1);
  return R;
}

// Compiled twice, for AVX2 (one 4-lane register per Lanes value, twice the registers of SSE2) and for the
// base x86-64 ISA, the loader picking the one the CPU runs (GCC function multi-versioning): 1.7x fewer
// cycles per fit measured (bench/polar_rotation_bench). Without FMA, so that both round alike.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void polar_rotation_near(const Eigen::Matrix3d* S, const Eigen::Matrix3d* guess, Eigen::Matrix3d* R, int count) {
  for (int first = 0; first < count; first += kLanes) {
    Lanes s[9] = {}, q[4] = {};
    LaneMask running = {};
    for (int l = 0; l < kLanes && first + l < count; ++l) {
      double s_row[9], q_row[4];
      if (!group_start(S[first + l], guess[first + l], s_row, q_row)) continue;
      running[l] = -1;
      for (int k = 0; k < 9; ++k) s[k][l] = s_row[k];
      for (int k = 0; k < 4; ++k) q[k][l] = q_row[k];
    }
    LaneMask converged;
    group_newton(s, q, running, converged);
    Lanes Rq[9];
    rotation_of(q, Rq);
    for (int l = 0; l < kLanes && first + l < count; ++l) {
      if (!converged[l]) {
        R[first + l] = polar_rotation(S[first + l]);
        continue;
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[first + l](i, j) = Rq[3 * i + j][l];
    }
  }
}

Eigen::Matrix3d planar_rotation(const Eigen::Matrix3d& S) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R.topLeftCorner<2, 2>() = closest_rotation_2d(S.topLeftCorner<2, 2>());
  return R;
}

} // namespace iarap
