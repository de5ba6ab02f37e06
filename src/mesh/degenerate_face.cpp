#include "iarap/mesh/cotan.h"
#include "iarap/mesh/validate.h"

#include <Eigen/Geometry>

#include <cmath>

namespace iarap {

bool is_degenerate_face(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c,
                        double bbox_diagonal) {
  // Non-finite corners are an error of their own (check_mesh names the vertex): not to be dropped as a face.
  if (!a.allFinite() || !b.allFinite() || !c.allFinite()) return false;
  if (0.5 * (b - a).cross(c - a).norm() <= 1e-12 * bbox_diagonal * bbox_diagonal) return true;
  // As face_cotangents computes them: from the lengths, over 4 x the area from the lengths.
  const double l[3] = {(b - c).norm(), (c - a).norm(), (a - b).norm()};
  const double four_area = 4.0 * triangle_area_from_lengths(l[0], l[1], l[2]);
  for (int k = 0; k < 3; ++k) {
    const double p = l[(k + 1) % 3], q = l[(k + 2) % 3];
    if (!std::isfinite((p * p + q * q - l[k] * l[k]) / four_area)) return true;
  }
  return false;
}

} // namespace iarap
