#include "correspondences.h"

#include "iarap/registration/point_index.h"

#include <algorithm>
#include <cmath>

namespace iarap::registration_detail {

namespace {

// The closest point to q on the deformed source or the target: over the triangles around the nearest point
// (or that point, for a point cloud). Normal interpolated from the points' normals.
SurfacePoint closest_on(const Eigen::Vector3d& q, const PointIndex& index, const Eigen::MatrixXd& P,
                        const Eigen::MatrixXi& F, const VertexFaces& around, const Eigen::MatrixXd& N,
                        Eigen::Vector3d& normal) {
  const auto [nearest, squared] = index.nearest(q);
  const int vertex = static_cast<int>(nearest);
  SurfacePoint point;
  if (F.rows() > 0) {
    point = closest_point_near_vertex(q, P, F, around, vertex);
  } else {
    point.position = P.row(vertex).transpose();
    point.squared_distance = squared;
  }
  if (point.face < 0) {
    normal = N.row(vertex).transpose();
  } else {
    normal = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) normal += point.barycentric(k) * N.row(F(point.face, k)).transpose();
    const double length = normal.norm();
    normal = length > 0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d(N.row(vertex).transpose());
  }
  return point;
}

Eigen::Vector3d pull(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& n,
                     double alpha) {
  const Eigen::Vector3d d = to - from;
  return (1 - alpha) * d + alpha * d.dot(n) * n;
}

} // namespace

double median(Eigen::VectorXd values) {
  if (values.size() == 0) return 0;
  const auto middle = values.data() + values.size() / 2;
  std::nth_element(values.data(), middle, values.data() + values.size());
  return *middle;
}

Eigen::VectorXd correspondence_weights(const Eigen::VectorXd& d, const Eigen::VectorXd& c, bool oriented,
                                       const CorrespondenceRules& rules) {
  const double limit = std::max(rules.reject_distance * median(d), rules.floor_distance);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(d.size());
  std::vector<double> kept;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    const double cosine = oriented ? c(i) : std::abs(c(i));
    if (d(i) <= limit && cosine >= rules.cos_reject_angle) {
      w(i) = 1;
      kept.push_back(d(i));
    }
  }
  const double sigma = std::max(
      rules.robust_scale *
          median(Eigen::Map<const Eigen::VectorXd>(kept.data(), static_cast<Eigen::Index>(kept.size()))),
      rules.floor_distance);
  if (sigma <= 0) return w;
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (w(i) > 0) w(i) = std::exp(-d(i) * d(i) / (2 * sigma * sigma)); // Welsch
  return w;
}

ClosestPoints closest_target_points(const Eigen::MatrixXd& U, const RegistrationTarget& target) {
  ClosestPoints closest;
  closest.position.resize(U.rows(), 3);
  closest.normal.resize(U.rows(), 3);
  closest.distance.resize(U.rows());
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < U.rows(); ++i) {
    Eigen::Vector3d normal;
    const SurfacePoint point = closest_on(U.row(i).transpose(), target.index, target.points, target.faces,
                                          target.around, target.normals, normal);
    closest.position.row(i) = point.position.transpose();
    closest.normal.row(i) = normal.transpose();
    closest.distance(i) = std::sqrt(point.squared_distance);
  }
  return closest;
}

VertexPulls forward_pulls(const Eigen::MatrixXd& U, const Eigen::MatrixXd& NU,
                          const RegistrationTarget& target, const CorrespondenceRules& rules) {
  const ClosestPoints closest = closest_target_points(U, target);
  const Eigen::VectorXd cosines = (NU.array() * closest.normal.array()).rowwise().sum();
  VertexPulls pulls;
  pulls.weight = correspondence_weights(closest.distance, cosines, target.oriented, rules);
  pulls.target = U;
  for (Eigen::Index i = 0; i < U.rows(); ++i) {
    if (pulls.weight(i) == 0) continue;
    ++pulls.used;
    pulls.target.row(i) += pull(U.row(i).transpose(), closest.position.row(i).transpose(),
                                closest.normal.row(i).transpose(), rules.point_to_plane)
                               .transpose();
  }
  pulls.mean_distance = closest.distance.mean();
  pulls.median_distance = median(closest.distance);
  return pulls;
}

VertexPulls backward_pulls(const Eigen::MatrixXd& U, const Eigen::MatrixXd& NU, const Eigen::MatrixXi& F,
                           const VertexFaces& around, const RegistrationTarget& target,
                           const CorrespondenceRules& rules) {
  const PointIndex source(U);
  const Eigen::Index n = target.points.rows();
  std::vector<SurfacePoint> points(static_cast<std::size_t>(n));
  Eigen::VectorXd d(n), cosines(n);
#pragma omp parallel for schedule(static)
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::Vector3d normal;
    const Eigen::Vector3d q = target.points.row(j).transpose();
    SurfacePoint& point = points[static_cast<std::size_t>(j)];
    point = closest_on(q, source, U, F, around, NU, normal);
    d(j) = std::sqrt(point.squared_distance);
    cosines(j) = normal.dot(target.normals.row(j).transpose());
  }
  const Eigen::VectorXd w = correspondence_weights(d, cosines, target.oriented, rules);
  VertexPulls pulls;
  pulls.weight = Eigen::VectorXd::Zero(U.rows());
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(U.rows(), 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    const SurfacePoint& point = points[static_cast<std::size_t>(j)];
    if (w(j) == 0 || point.face < 0) continue;
    ++pulls.used;
    const Eigen::RowVector3d delta = pull(point.position, target.points.row(j).transpose(),
                                          target.normals.row(j).transpose(), rules.point_to_plane)
                                         .transpose();
    for (int k = 0; k < 3; ++k) {
      const int v = F(point.face, k);
      const double share = w(j) * point.barycentric(k);
      pulls.weight(v) += share;
      sum.row(v) += share * (U.row(v) + delta);
    }
  }
  pulls.target = U;
  for (Eigen::Index v = 0; v < U.rows(); ++v)
    if (pulls.weight(v) > 0) pulls.target.row(v) = sum.row(v) / pulls.weight(v);
  pulls.mean_distance = d.mean();
  pulls.median_distance = median(d);
  return pulls;
}

} // namespace iarap::registration_detail
