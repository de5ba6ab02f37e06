#include "prealign.h"

#include "iarap/registration/surface_normals.h"

#include <cmath>

namespace iarap::registration_detail {

namespace {

// Centroids matched, and (with scale) the RMS distances to them.
SimilarityTransform centroid_start(const Eigen::MatrixXd& V, const Eigen::MatrixXd& P, bool with_scale) {
  SimilarityTransform T;
  const Eigen::RowVector3d cv = V.colwise().mean(), cp = P.colwise().mean();
  if (with_scale) {
    const double rv = std::sqrt((V.rowwise() - cv).rowwise().squaredNorm().mean());
    const double rp = std::sqrt((P.rowwise() - cp).rowwise().squaredNorm().mean());
    if (rv > 0 && rp > 0) T.s = rp / rv;
  }
  T.t = (cp - T.s * cv).transpose();
  return T;
}

double change(const SimilarityTransform& a, const SimilarityTransform& b, double diagonal) {
  return (a.R - b.R).norm() + std::abs(a.s - b.s) + (a.t - b.t).norm() / diagonal;
}

} // namespace

PrealignResult prealign(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RegistrationTarget& target,
                        const LandmarkPoints& landmarks, bool with_scale, int rounds,
                        const CorrespondenceRules& rules) {
  PrealignResult result;
  const Eigen::Index n = V.rows(), l = landmarks.source.rows();
  result.transform = l >= 3 ? fit_similarity(landmarks.source, landmarks.target, landmarks.weight, with_scale)
                            : centroid_start(V, target.points, with_scale);
  const Eigen::MatrixXd N = area_weighted_vertex_normals(V, F);
  Eigen::MatrixXd P(n + l, 3), Q(n + l, 3);
  Eigen::VectorXd w(n + l);
  P.topRows(n) = V;
  if (l > 0) {
    P.bottomRows(l) = landmarks.source;
    Q.bottomRows(l) = landmarks.target;
    w.tail(l) = landmarks.weight;
  }
  for (; result.rounds < rounds; ++result.rounds) {
    const SimilarityTransform& T = result.transform;
    const ClosestPoints closest = closest_target_points(T.apply(V), target);
    const Eigen::VectorXd cosines = ((N * T.R.transpose()).array() * closest.normal.array()).rowwise().sum();
    w.head(n) = correspondence_weights(closest.distance, cosines, target.oriented, rules);
    Q.topRows(n) = closest.position;
    if (!(w.sum() > 0)) break;
    const SimilarityTransform next = fit_similarity(P, Q, w, with_scale);
    const double moved = change(next, T, target.diagonal);
    result.transform = next;
    if (moved < 1e-12) {
      ++result.rounds;
      break;
    }
  }
  return result;
}

} // namespace iarap::registration_detail
