// How far a triangle can move along a straight line of UV maps before it degenerates: the step bound of
// injectivity-preserving line searches (Smith and Schaefer 2015, Sec. 4).
#pragma once
#include <Eigen/Core>

namespace iarap {

// With J(t) = J0 + t (J1 - J0), det J(t) = det J0 + t b + t^2 det(J1 - J0) is a quadratic in t. Returns
// its smallest root t > 0, +infinity when det J(t) > 0 for every t > 0. Meant for det J0 > 0 (the
// triangle is not flipped); for det J0 <= 0 returns +infinity too (such a triangle cannot flip further
// and does not limit the step). Roots by the cancellation-free quadratic formula.
double first_degenerate_step(const Eigen::Matrix2d& J0, const Eigen::Matrix2d& J1);

} // namespace iarap
