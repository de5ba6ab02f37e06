// Internal: the rigid (or similarity) pre-alignment of registration: a start from the landmarks (three or
// more) or the centroids, refined by rigid ICP, each round fit_similarity of the source's vertices to their
// closest target points (rejection and robust weights as correspondences.h) together with the landmarks.
#pragma once
#include "correspondences.h"
#include "iarap/registration/rigid_alignment.h"

#include <Eigen/Core>

namespace iarap::registration_detail {

// Landmark points of the source (#L x 3 rest positions), their targets (#L x 3) and weights (#L).
struct LandmarkPoints {
  Eigen::MatrixXd source, target;
  Eigen::VectorXd weight;
};

struct PrealignResult {
  SimilarityTransform transform;
  int rounds = 0; // ICP rounds run
};

// V #V x 3 (faces F for the normals), at most `rounds` ICP rounds; stops when the transform moves by less
// than 1e-12 (relative to the target's diagonal).
PrealignResult prealign(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RegistrationTarget& target,
                        const LandmarkPoints& landmarks, bool with_scale, int rounds,
                        const CorrespondenceRules& rules);

} // namespace iarap::registration_detail
