#include "iarap/param/map_distortion.h"

#include "iarap/solver/closest_rotation_2d.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace iarap {

namespace {

DistortionRange range_of(std::vector<double> values) {
  DistortionRange r;
  if (values.empty()) return r;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  r.median = *middle;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  r.min = *low;
  r.max = *high;
  return r;
}

} // namespace

Eigen::Vector2d singular_values_2d(const Eigen::Matrix2d& J) {
  // J = similarity part + anti-similarity part; |q| and |r| are their scales, sigma = |q| +- |r|.
  const double q = 0.5 * std::hypot(J(0, 0) + J(1, 1), J(1, 0) - J(0, 1));
  const double r = 0.5 * std::hypot(J(0, 0) - J(1, 1), J(1, 0) + J(0, 1));
  return {q + r, std::abs(q - r)};
}

MapDistortion map_distortion(const TriangleFrames& frames, const Eigen::MatrixXi& F,
                             const Eigen::MatrixXd& UV) {
  MapDistortion d;
  const auto nf = static_cast<std::size_t>(F.rows());
  std::vector<double> area_ratio(nf), angle_ratio(nf);
  std::vector<Eigen::Matrix2d> rotation(nf);
  double trace_sum = 0, norm_sum = 0; // sum_f area_f tr(R_f^T J_f), sum_f area_f ||J_f||^2
  d.min_det_J = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Matrix2d J = face_jacobian(frames, F, UV, f);
    const Eigen::Matrix2d R = closest_rotation_2d(J);
    const double a = frames.area(f), det = J.determinant();
    d.energy += a * (J - R).squaredNorm();
    trace_sum += a * (R.transpose() * J).trace();
    norm_sum += a * J.squaredNorm();
    rotation[static_cast<std::size_t>(f)] = R;
    if (det <= 0) ++d.flipped;
    d.min_det_J = std::min(d.min_det_J, det);
    const Eigen::Vector2d sigma = singular_values_2d(J);
    area_ratio[static_cast<std::size_t>(f)] = sigma(0) * sigma(1);
    angle_ratio[static_cast<std::size_t>(f)] =
        sigma(1) > 0 ? sigma(0) / sigma(1) : std::numeric_limits<double>::infinity();
  }
  // E(s) = s^2 sum a ||J||^2 - 2 s sum a tr(R^T J) + 2 sum a is least at s = trace_sum / norm_sum (the R_f
  // do not depend on s > 0); E(s) is summed again rather than taken from the closed form, which cancels.
  d.best_scale = norm_sum > 0 && trace_sum > 0 ? trace_sum / norm_sum : 1.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    d.scaled_energy += frames.area(f) * (d.best_scale * face_jacobian(frames, F, UV, f) -
                                         rotation[static_cast<std::size_t>(f)])
                                            .squaredNorm();
  d.area_ratio = range_of(std::move(area_ratio));
  d.angle_ratio = range_of(std::move(angle_ratio));
  return d;
}

} // namespace iarap
