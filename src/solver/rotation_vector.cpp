#include "rotation_vector.h"

#include <Eigen/Geometry>

#include <cmath>

namespace iarap::detail {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {
  Eigen::Matrix3d W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return W;
}

namespace {

constexpr double kSeries = 1e-2; // below this theta the Taylor series (error ~theta^4 / 5040 relative)

// sin theta / theta, a = (1 - cos theta) / theta^2, b = (theta - sin theta) / theta^3 and the derivatives
// a' / theta, b' / theta (the gradients of a and b in w are a' w / theta, b' w / theta).
struct Coefficients {
  double sinc, a, b, da, db;
};

Coefficients coefficients(double theta) {
  const double t2 = theta * theta;
  if (theta < kSeries)
    return {1 - t2 / 6 + t2 * t2 / 120, 0.5 - t2 / 24 + t2 * t2 / 720, 1.0 / 6 - t2 / 120 + t2 * t2 / 5040,
            -1.0 / 12 + t2 / 180, -1.0 / 60 + t2 / 1260};
  const double s = std::sin(theta), c = std::cos(theta);
  return {s / theta, (1 - c) / t2, (theta - s) / (t2 * theta), (theta * s - 2 * (1 - c)) / (t2 * t2),
          (theta * (1 - c) - 3 * (theta - s)) / (t2 * t2 * theta)};
}

} // namespace

Eigen::Matrix3d rotation_of_vector(const Eigen::Vector3d& w) {
  const Coefficients k = coefficients(w.norm());
  const Eigen::Matrix3d W = cross_matrix(w);
  return Eigen::Matrix3d::Identity() + k.sinc * W + k.a * W * W;
}

Eigen::Vector3d rotation_vector_of(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd turn(R); // by the quaternion: accurate near the identity and near pi
  return turn.angle() * turn.axis();
}

Eigen::Matrix3d left_jacobian(const Eigen::Vector3d& w) {
  const Coefficients k = coefficients(w.norm());
  const Eigen::Matrix3d W = cross_matrix(w);
  return Eigen::Matrix3d::Identity() + k.a * W + k.b * W * W;
}

// J^T tau = tau - a (w x tau) + b w x (w x tau), differentiated term by term: d(w x tau)/dw = -[tau]x and
// d(w x (w x tau))/dw = d(w (w.tau) - tau |w|^2)/dw = (w.tau) I + w tau^T - 2 tau w^T.
Eigen::Matrix3d left_jacobian_transpose_derivative(const Eigen::Vector3d& w, const Eigen::Vector3d& tau) {
  const Coefficients k = coefficients(w.norm());
  const Eigen::Vector3d wt = w.cross(tau), wwt = w.cross(wt);
  return -k.da * wt * w.transpose() + k.a * cross_matrix(tau) + k.db * wwt * w.transpose() +
         k.b * (w.dot(tau) * Eigen::Matrix3d::Identity() + w * tau.transpose() - 2 * tau * w.transpose());
}

} // namespace iarap::detail
