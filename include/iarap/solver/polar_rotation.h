// The rotation closest to a 3x3 matrix: the local step of every ARAP variant (paper Sec. 4.2, Eq. 15).
#pragma once
#include <Eigen/Core>

namespace iarap {

// The rotation R (R^T R = I, det R = +1) maximizing tr(R^T S), i.e. the rotation of the polar
// decomposition S = R T when det S > 0. Handles every S:
//   - det S <= 0 (a reflection or rank deficiency): the smallest singular direction is flipped, which
//     is optimal among rotations; for rank 2 or 1 this is one of the optimal rotations;
//   - S = 0: the identity.
// S symmetric positive definite gives the identity: exactly when S is bitwise symmetric (the rest state
// of ARAP), else to rounding (~1e-15 / (sigma_2 + sigma_3) relative to |S|); this keeps an undeformed
// mesh at rest. Scale-free: polar_rotation(c * S) == polar_rotation(S) for c > 0.
// Well-conditioned S with det S > 0 (the common case in ARAP) take a scaled Newton iteration
// (Higham); the rest a fixed-size 3x3 JacobiSVD. Non-finite entries give a non-finite result.
Eigen::Matrix3d polar_rotation(const Eigen::Matrix3d& S);

// polar_rotation(S) (the same rotation to rounding) found from a guess near it, e.g. the cell's rotation
// of the previous ARAP iteration: Newton steps on the rotation group, two or three when the guess is
// within a few degrees, against the five to eight of polar_rotation's iteration. It covers det S <= 0 and
// near rank deficiency as well (polar_rotation takes its SVD there) as long as the optimum is unique with
// a margin (sigma_2 + sigma_3 > 1e-6 |S|, sigma_3 signed like det S). Whenever the guess is far (first
// step over 0.5 rad), the quadratic model is not safely concave there, or S is bitwise symmetric (the
// exact rest state), S = 0 or non-finite: polar_rotation(S) itself.
Eigen::Matrix3d polar_rotation_near(const Eigen::Matrix3d& S, const Eigen::Matrix3d& guess);

// R[k] = polar_rotation_near(S[k], guess[k]) for k < count, the same rotations bit for bit, four fits at a
// time in lockstep: their Newton steps interleave (and vectorize) instead of each waiting on its own
// chain of dependent operations. What the ARAP local step calls.
void polar_rotation_near(const Eigen::Matrix3d* S, const Eigen::Matrix3d* guess, Eigen::Matrix3d* R,
                         int count);

// The rotation about the z axis maximizing tr(R^T S) for a planar cell (S's third row and column are zero:
// positions and rest vectors in the xy plane): closest_rotation_2d of S's upper-left 2x2 block, with
// R(2, 2) = 1. Unlike polar_rotation it never returns a rotation that turns the plane over (which is what
// polar_rotation gives for det S_2x2 < 0): a planar mesh deformed in its plane keeps 2x2 rotations. At rest
// (S_2x2 bitwise symmetric with positive trace) it is exactly the identity.
Eigen::Matrix3d planar_rotation(const Eigen::Matrix3d& S);

} // namespace iarap
