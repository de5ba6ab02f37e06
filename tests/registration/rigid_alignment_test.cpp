// Umeyama's fit and the ICP pre-alignment recover a known transform of exact data.
#include "iarap/registration/registration_target.h"
#include "iarap/registration/rigid_alignment.h"
#include "registration/prealign.h"
#include "registration_fixtures.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace iarap {
namespace {

SimilarityTransform known_transform(double scale) {
  SimilarityTransform T;
  T.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  T.t = Eigen::Vector3d(0.3, -0.2, 0.5);
  T.s = scale;
  return T;
}

void expect_same(const SimilarityTransform& got, const SimilarityTransform& want, double tolerance) {
  EXPECT_LT((got.R - want.R).norm(), tolerance);
  EXPECT_LT((got.t - want.t).norm(), tolerance);
  EXPECT_NEAR(got.s, want.s, tolerance);
}

TEST(FitSimilarity, RecoversARotationTranslationAndScale) {
  const MeshData mesh = read_mesh(test::data_path("bunny.off"));
  for (const double scale : {1.0, 2.5}) {
    const SimilarityTransform want = known_transform(scale);
    const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(mesh.V.rows(), 0.5, 2.0);
    expect_same(fit_similarity(mesh.V, want.apply(mesh.V), w, scale != 1.0), want, 1e-9);
  }
}

TEST(FitSimilarity, RejectsBadWeights) {
  const Eigen::MatrixXd P = Eigen::MatrixXd::Random(4, 3);
  EXPECT_THROW(fit_similarity(P, P, Eigen::VectorXd::Zero(4)), InputError);
  EXPECT_THROW(fit_similarity(P, P, Eigen::VectorXd::Constant(4, -1)), InputError);
  EXPECT_THROW(fit_similarity(P, P.topRows(3), Eigen::VectorXd::Ones(4)), InputError);
}

// The pre-alignment of `iarap register`: four landmarks give the start, rigid ICP onto the transformed
// vertices (a point cloud: PCA normals) keeps the exact answer.
TEST(Prealign, RecoversAKnownRigidMotionOnExactData) {
  const test::OneThread one_thread;
  const MeshData mesh = read_mesh(test::data_path("bunny.off"));
  const SimilarityTransform want = known_transform(1.0);
  const RegistrationTarget target = make_registration_target(want.apply(mesh.V), {}, {}, "moved bunny");
  registration_detail::LandmarkPoints landmarks;
  const std::vector<int> picked = {0, 900, 1800, 2700};
  landmarks.source.resize(4, 3);
  for (int k = 0; k < 4; ++k) landmarks.source.row(k) = mesh.V.row(picked[static_cast<std::size_t>(k)]);
  landmarks.target = want.apply(landmarks.source);
  landmarks.weight = Eigen::VectorXd::Constant(4, 100.0);
  registration_detail::CorrespondenceRules rules;
  rules.floor_distance = 1e-12 * target.diagonal;
  const auto result = registration_detail::prealign(mesh.V, mesh.F, target, landmarks, false, 50, rules);
  expect_same(result.transform, want, 1e-9);
}

// Without landmarks, from the centroids: a small rotation is found by the ICP rounds alone.
TEST(Prealign, RecoversASmallRotationFromTheCentroids) {
  const test::OneThread one_thread;
  const MeshData mesh = read_mesh(test::data_path("bunny.off"));
  SimilarityTransform want;
  want.R = Eigen::AngleAxisd(0.05, Eigen::Vector3d(0, 1, 0)).toRotationMatrix();
  want.t = Eigen::Vector3d(0.01, 0.02, -0.01);
  const RegistrationTarget target = make_registration_target(want.apply(mesh.V), {}, mesh.F, "moved bunny");
  registration_detail::CorrespondenceRules rules;
  rules.floor_distance = 1e-12 * target.diagonal;
  const auto result = registration_detail::prealign(mesh.V, mesh.F, target,
                                                    registration_detail::LandmarkPoints{}, false, 200, rules);
  expect_same(result.transform, want, 1e-9);
}

} // namespace
} // namespace iarap
