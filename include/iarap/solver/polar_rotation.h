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

} // namespace iarap
