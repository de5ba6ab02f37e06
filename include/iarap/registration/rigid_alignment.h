// The similarity (or rigid) transform that best maps points onto corresponding points in the weighted
// least-squares sense: Kabsch's rotation, with Umeyama's scale and reflection guard (Umeyama 1991,
// "Least-squares estimation of transformation parameters between two point patterns").
#pragma once
#include <Eigen/Core>

namespace iarap {

// x -> s R x + t.
struct SimilarityTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity(); // a rotation (det +1)
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double s = 1.0;
  // Each row of P (#P x 3) mapped.
  Eigen::MatrixXd apply(const Eigen::MatrixXd& P) const;
};

// argmin over R, t (and s > 0 when with_scale) of sum_i w_i |s R p_i + t - q_i|^2 for P, Q #n x 3 and
// weights w (#n, >= 0, finite, positive sum). With fewer than three non-collinear points the rotation is not
// unique and one of the minimizers is returned. Throws InputError for shapes that differ, a bad weight or a
// zero weight sum.
SimilarityTransform fit_similarity(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q,
                                   const Eigen::VectorXd& w, bool with_scale = false);

} // namespace iarap
