// The power of two that brings a mesh's coordinates near 1, so that its geometry can be computed at any
// scale: areas and squared lengths of a mesh at 1e200 overflow and at 1e-200 underflow, while the same
// mesh divided by 2^k computes exactly as at size 1 (a power-of-two scale changes no significant bit).
#pragma once
#include <Eigen/Core>

namespace iarap {

// A power of two s such that the largest finite |coordinate| of V (#V x 3) divided by s lies in [0.5, 1);
// 1 when V has no finite non-zero coordinate. V / s and s * U are exact (away from subnormals).
double normalizing_scale(const Eigen::MatrixXd& V);

} // namespace iarap
