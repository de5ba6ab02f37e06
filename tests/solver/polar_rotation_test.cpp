#include "iarap/solver/polar_rotation.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <vector>

namespace {

using Eigen::Matrix3d;
using iarap::polar_rotation;

Matrix3d random_matrix(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Matrix3d A;
  for (int i = 0; i < 9; ++i) A(i) = n(rng);
  return A;
}

Matrix3d random_rotation(std::mt19937& rng) {
  Eigen::HouseholderQR<Matrix3d> qr(random_matrix(rng));
  Matrix3d Q = qr.householderQ();
  if (Q.determinant() < 0) Q.col(0) = -Q.col(0);
  return Q;
}

// Reference: U diag(1, 1, det(U V^T)) V^T from a JacobiSVD.
Matrix3d svd_rotation(const Matrix3d& S) {
  Eigen::JacobiSVD<Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Matrix3d U = svd.matrixU();
  if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * svd.matrixV().transpose();
}

void expect_rotation(const Matrix3d& R) {
  EXPECT_LT((R.transpose() * R - Matrix3d::Identity()).norm(), 1e-14);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
}

TEST(PolarRotation, RandomMatricesMatchSvdAndBeatRandomRotations) {
  std::mt19937 rng(11);
  for (int t = 0; t < 2000; ++t) {
    const Matrix3d S = random_matrix(rng);
    const Matrix3d R = polar_rotation(S);
    expect_rotation(R);
    // The polar factor is unique when sigma_2 + sigma_3 > 0; its sensitivity is eps / (sigma_2 + sigma_3).
    const Eigen::Vector3d sigma = Eigen::JacobiSVD<Matrix3d>(S).singularValues();
    EXPECT_LT((R - svd_rotation(S)).norm(), 1e-13 * sigma(0) / (sigma(1) + sigma(2))) << "trial " << t;
    const double best = (R.transpose() * S).trace();
    for (int k = 0; k < 5; ++k) EXPECT_GE(best + 1e-12, (random_rotation(rng).transpose() * S).trace());
  }
}

TEST(PolarRotation, ReflectionFlipsTheSmallestDirection) {
  const Matrix3d S = Eigen::Vector3d(3.0, 2.0, -1.0).asDiagonal(); // det < 0
  const Matrix3d R = polar_rotation(S);
  expect_rotation(R);
  EXPECT_LT((R - Matrix3d::Identity()).norm(), 1e-15); // flipping the -1 back costs least: tr = 3 + 2 - 1
  std::mt19937 rng(5);
  for (int t = 0; t < 200; ++t) {
    const Matrix3d P = random_rotation(rng), Q = random_rotation(rng);
    const Matrix3d A = P * Eigen::Vector3d(4.0, 1.5, -0.5).asDiagonal() * Q.transpose();
    const Matrix3d Ra = polar_rotation(A);
    expect_rotation(Ra);
    EXPECT_LT((Ra - P * Q.transpose()).norm(), 1e-13);
  }
}

TEST(PolarRotation, RankDeficientGivesAnOptimalRotation) {
  std::mt19937 rng(9);
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3d a = random_matrix(rng).col(0), b = random_matrix(rng).col(1);
    const Eigen::Vector3d c = random_matrix(rng).col(2), d = random_matrix(rng).col(0);
    for (const Matrix3d& S : {Matrix3d(a * b.transpose()), Matrix3d(a * b.transpose() + c * d.transpose())}) {
      const Matrix3d R = polar_rotation(S);
      expect_rotation(R);
      const double optimum = Eigen::JacobiSVD<Matrix3d>(S).singularValues().sum(); // max of tr(R^T S)
      EXPECT_NEAR((R.transpose() * S).trace(), optimum, 1e-13 * optimum);
    }
  }
}

TEST(PolarRotation, ZeroGivesIdentity) {
  EXPECT_EQ(polar_rotation(Matrix3d::Zero()), Matrix3d::Identity());
}

TEST(PolarRotation, NearIdentityAndScaleFree) {
  std::mt19937 rng(3);
  for (int t = 0; t < 200; ++t) {
    const Matrix3d Q = random_rotation(rng);
    const Matrix3d S = Q * (Matrix3d::Identity() + 1e-9 * random_matrix(rng));
    const Matrix3d R = polar_rotation(S);
    expect_rotation(R);
    EXPECT_LT((R - svd_rotation(S)).norm(), 1e-14);
    for (double scale : {1e-150, 1e150}) EXPECT_LT((polar_rotation(scale * S) - R).norm(), 1e-14);
  }
}

// The rest state of ARAP has symmetric positive (semi)definite covariances: any error here is a
// rotation that moves an undeformed mesh. Exactly symmetric and positive definite: exactly I. Cell
// covariances have two tangential eigenvalues of similar size and a normal one down to 0 (flat
// one-rings); where rounding makes the minors test fail, the sensitivity of the answer is
// eps / (lambda_2 + lambda_3), hence lambda_2 >= 0.1 for the few-ulps bound.
TEST(PolarRotation, SymmetricPositiveDefiniteGivesIdentity) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent2(-1.0, 0.0), exponent3(-16.0, 0.0);
  int exact = 0;
  for (int t = 0; t < 5000; ++t) {
    const Matrix3d Q = random_rotation(rng);
    const Eigen::Vector3d lambda(1.0, std::pow(10.0, exponent2(rng)), std::pow(10.0, exponent3(rng)));
    Matrix3d S = Q * lambda.asDiagonal() * Q.transpose();
    S = (0.5 * (S + S.transpose())).eval(); // exactly symmetric
    const Matrix3d R = polar_rotation(S);
    EXPECT_LT((R - Matrix3d::Identity()).cwiseAbs().maxCoeff(), 2e-15) << "trial " << t;
    exact += R == Matrix3d::Identity();
    if (lambda(2) > 1e-8) {
      EXPECT_EQ(R, Matrix3d::Identity()) << "trial " << t;
    }
  }
  EXPECT_GT(exact, 2500);
}

// Nearly symmetric (rounding-level asymmetry, as in a slightly deformed state): Newton and refinement.
TEST(PolarRotation, NearlySymmetricGivesTheExactPolarFactor) {
  std::mt19937 rng(8);
  for (int t = 0; t < 2000; ++t) {
    const Matrix3d Q = random_rotation(rng);
    const Eigen::Vector3d d = Eigen::Vector3d::Ones() + 0.5 * random_matrix(rng).col(0).cwiseAbs();
    const Matrix3d S =
        Q * d.asDiagonal() * Q.transpose(); // products round differently above and below the diagonal
    const Matrix3d R = polar_rotation(S);
    expect_rotation(R);
    EXPECT_LT((R - svd_rotation(S)).norm(), 1e-14) << "trial " << t;
  }
}

// polar_rotation_near from a guess a few degrees off (what the iterations hand it) on the covariances
// polar_rotation sends to its SVD: reflections (det S < 0, frequent with original ARAP's negative weights)
// and rank 2 up to rounding (flat one-rings). The optimum is unique with sigma_2 + sigma_3 >= 0.1 here
// (sigma_3 signed like det S), so both answers are the one rotation to rounding: eps / (sigma_2 + sigma_3)
// ~ 1e-15, hence 1e-13.
TEST(PolarRotation, NearGuessMatchesSvdOnReflectionsAndRankDeficiency) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> second(0.3, 1.0), third(-0.2, 0.2), angle(-0.05, 0.05);
  for (int t = 0; t < 2000; ++t) {
    const Matrix3d P = random_rotation(rng), Q = random_rotation(rng);
    const double sigma3 = t % 4 == 0 ? 0.0 : t % 4 == 1 ? 1e-14 * third(rng) : third(rng);
    const Matrix3d S = P * Eigen::Vector3d(1.0, second(rng), sigma3).asDiagonal() * Q.transpose();
    const Matrix3d optimum = svd_rotation(S);
    const Matrix3d guess =
        optimum * Eigen::AngleAxisd(angle(rng), random_matrix(rng).col(0).normalized()).toRotationMatrix();
    const Matrix3d R = iarap::polar_rotation_near(S, guess);
    expect_rotation(R);
    EXPECT_LT((R - optimum).norm(), 1e-13) << "trial " << t;
    EXPECT_LT((R - polar_rotation(S)).norm(), 1e-13) << "trial " << t;
  }
}

TEST(PolarRotation, NonFiniteInputGivesNonFiniteOutput) {
  Matrix3d S = Matrix3d::Identity();
  S(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(polar_rotation(S).allFinite());
  // The warm-started fit has no finiteness test of its own: NaN or infinity must reach polar_rotation.
  const Matrix3d guess = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_FALSE(iarap::polar_rotation_near(S, guess).allFinite());
  S(1, 2) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(iarap::polar_rotation_near(S, guess).allFinite());
  Matrix3d bad_guess = guess;
  bad_guess(0, 1) = std::numeric_limits<double>::quiet_NaN();
  S(1, 2) = 0.3;
  EXPECT_LT((iarap::polar_rotation_near(S, bad_guess) - polar_rotation(S)).norm(), 1e-15);
}

// The batched fit (four in lockstep, what the local step calls) returns exactly the single fits, whatever
// path each lane takes: Newton from a near guess (most), the cold iteration for a far guess, a bitwise
// symmetric S (rest state) or a rank-1 S where the model is not concave, S = 0, NaN. Exact equality: each
// lane does the same IEEE operations as a fit on its own. 4k + 3 fits, so the last block is partial.
TEST(PolarRotation, BatchedNearFitsEqualSingleFits) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> angle(-0.05, 0.05);
  std::vector<Matrix3d> S, guess;
  for (int t = 0; t < 203; ++t) {
    Matrix3d St = random_matrix(rng);
    const Eigen::Vector3d axis = random_matrix(rng).col(0).normalized();
    double turn = angle(rng);
    switch (t % 9) {
    case 3:
      turn = 2.0;
      break; // far guess
    case 5:
      St = St * St.transpose();
      break; // symmetric
    case 6:
      St = random_matrix(rng).col(0) * random_matrix(rng).col(0).transpose();
      break; // rank 1
    case 7:
      St.setZero();
      break;
    case 8:
      St(2, 0) = t % 2 ? std::numeric_limits<double>::quiet_NaN() : St(2, 0);
      break;
    default:
      break;
    }
    S.push_back(St);
    guess.push_back(svd_rotation(St.allFinite() ? St : Matrix3d::Identity()) *
                    Eigen::AngleAxisd(turn, axis).toRotationMatrix());
  }
  std::vector<Matrix3d> batched(S.size());
  iarap::polar_rotation_near(S.data(), guess.data(), batched.data(), static_cast<int>(S.size()));
  for (size_t t = 0; t < S.size(); ++t) {
    const Matrix3d single = iarap::polar_rotation_near(S[t], guess[t]);
    if (!single.allFinite()) {
      EXPECT_FALSE(batched[t].allFinite()) << "fit " << t;
      continue;
    }
    EXPECT_TRUE(batched[t] == single) << "fit " << t << "\n" << batched[t] << "\nvs\n" << single;
    expect_rotation(batched[t]);
  }
}

} // namespace
