#include "iarap/registration/surface_normals.h"

#include "iarap/core/errors.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <vector>

namespace iarap {

Eigen::MatrixXd area_weighted_vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose(); // |n| = twice the area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double length = N.row(v).norm();
    if (length > 0) N.row(v) /= length;
  }
  return N;
}

Eigen::MatrixXd estimate_point_normals(const Eigen::MatrixXd& P, const PointIndex& index, int k,
                                       const std::string& source) {
  if (P.rows() < 3) {
    throw InputError(source + ": " + std::to_string(P.rows()) +
                     " points; need at least 3 points to estimate normals");
  }
  if (k < 3) throw InputError(source + ": normal_neighbours is " + std::to_string(k) + "; need at least 3");
  const Eigen::RowVector3d centroid = P.colwise().mean();
  Eigen::MatrixXd N(P.rows(), 3);
#pragma omp parallel
  {
    std::vector<Eigen::Index> near;
    std::vector<double> squared;
#pragma omp for schedule(static)
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      index.nearest_k(P.row(i).transpose(), k, near, squared);
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const Eigen::Index j : near) mean += P.row(j).transpose();
      mean /= static_cast<double>(near.size());
      Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
      for (const Eigen::Index j : near) {
        const Eigen::Vector3d d = P.row(j).transpose() - mean;
        C += d * d.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(C); // eigenvalues increasing
      Eigen::Vector3d n = eigen.eigenvectors().col(0);
      if (n.dot(P.row(i) - centroid) < 0) n = -n;
      N.row(i) = n.transpose();
    }
  }
  return N;
}

} // namespace iarap
