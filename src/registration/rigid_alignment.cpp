#include "iarap/registration/rigid_alignment.h"

#include "iarap/core/errors.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>
#include <string>

namespace iarap {

Eigen::MatrixXd SimilarityTransform::apply(const Eigen::MatrixXd& P) const {
  return ((s * P * R.transpose()).rowwise() + t.transpose()).eval();
}

SimilarityTransform fit_similarity(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q,
                                   const Eigen::VectorXd& w, bool with_scale) {
  if (P.cols() != 3 || Q.cols() != 3 || P.rows() != Q.rows() || w.size() != P.rows()) {
    throw InputError("fit_similarity: P and Q must be #n x 3 and w #n; got P " + std::to_string(P.rows()) +
                     " x " + std::to_string(P.cols()) + ", Q " + std::to_string(Q.rows()) + " x " +
                     std::to_string(Q.cols()) + ", w " + std::to_string(w.size()));
  }
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    if (!(std::isfinite(w(i)) && w(i) >= 0))
      throw InputError("fit_similarity: weight " + std::to_string(i) + " is " + std::to_string(w(i)) +
                       "; weights must be finite and >= 0");
  }
  const double total = w.sum();
  if (!(total > 0)) throw InputError("fit_similarity: the weights sum to 0");
  const Eigen::Vector3d p_mean = (P.transpose() * w) / total, q_mean = (Q.transpose() * w) / total;
  const Eigen::MatrixXd Pc = P.rowwise() - p_mean.transpose(), Qc = Q.rowwise() - q_mean.transpose();
  // Sigma = sum_i w_i (q_i - q_mean)(p_i - p_mean)^T / total (Umeyama's Eq. 38).
  const Eigen::Matrix3d Sigma = (Qc.transpose() * w.asDiagonal() * Pc) / total;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(Sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d d = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) d(2) = -1; // no reflection (Eq. 39)
  SimilarityTransform T;
  T.R = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
  if (with_scale) {
    const double variance = (Pc.rowwise().squaredNorm().transpose() * w)(0) / total; // Eq. 36
    if (variance > 0) T.s = svd.singularValues().dot(d) / variance;                  // Eq. 42
  }
  T.t = q_mean - T.s * T.R * p_mean; // Eq. 41
  return T;
}

} // namespace iarap
