#include "iarap/param/injective_step.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace iarap {

double first_degenerate_step(const Eigen::Matrix2d& J0, const Eigen::Matrix2d& J1) {
  constexpr double none = std::numeric_limits<double>::infinity();
  const Eigen::Matrix2d D = J1 - J0;
  const double a = J0.determinant();
  if (!(a > 0)) return none;
  // det(J0 + t D) = a + b t + c t^2.
  const double b = J0(0, 0) * D(1, 1) + J0(1, 1) * D(0, 0) - J0(0, 1) * D(1, 0) - J0(1, 0) * D(0, 1);
  const double c = D.determinant();
  const double discriminant = b * b - 4 * a * c;
  if (discriminant < 0 || (b == 0 && c == 0)) return none;
  // q = -(b + sign(b) sqrt(disc)) / 2; the roots are q / c and a / q, neither computed by cancellation.
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  double t = none;
  if (c != 0 && q / c > 0) t = q / c;
  if (q != 0 && a / q > 0 && a / q < t) t = a / q;
  return t;
}

} // namespace iarap
