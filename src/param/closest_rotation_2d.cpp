#include "iarap/param/closest_rotation_2d.h"

#include <cmath>

namespace iarap {

Eigen::Matrix2d closest_rotation_2d(const Eigen::Matrix2d& J) {
  const double c = J(0, 0) + J(1, 1), s = J(1, 0) - J(0, 1); // 2 |J's similarity part| (cos, sin)
  // sqrt, not hypot (five times slower, and J of a map at the mesh's own scale is far from overflow).
  const double norm = std::sqrt(c * c + s * s);
  Eigen::Matrix2d R;
  if (norm == 0) return Eigen::Matrix2d::Identity();
  R << c / norm, -s / norm, s / norm, c / norm;
  return R;
}

} // namespace iarap
