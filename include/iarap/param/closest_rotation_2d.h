// The 2x2 rotation closest to a 2x2 matrix: the local step of ARAP parameterization (Liu et al. 2008).
#pragma once
#include <Eigen/Core>

namespace iarap {

// The rotation R (R^T R = I, det R = +1) that minimizes ||J - R||_F. Write J = [a b; c d]; then
// ||J - R(theta)||^2 = ||J||^2 + 2 - 2 ((a + d) cos theta + (c - b) sin theta), so the minimizer is
// theta = atan2(c - b, a + d): the similarity part of J, normalized. No SVD, no branch on det J: a J with
// det J < 0 (a flipped triangle) gets the closest rotation, never the reflection the polar decomposition
// would give, and a rank-1 J gets a rotation like any other. When a + d = c - b = 0 (J = 0, or J a
// symmetric matrix of zero trace such as the reflection diag(1, -1)) every rotation is equally close and
// the identity is returned. A J with a NaN entry gives NaN entries.
Eigen::Matrix2d closest_rotation_2d(const Eigen::Matrix2d& J);

} // namespace iarap
