// Cost of one rotation fit (the ARAP local step's inner call), cold (polar_rotation) and from a nearby
// guess (polar_rotation_near, what the iterations call), against a plain fixed-size JacobiSVD,
// on the matrices ARAP meets: general, near a rotation (converged iterations), symmetric positive
// definite (the rest state) and rank 2 (flat one-rings).
#include "iarap/solver/polar_rotation.h"

#include <Eigen/Dense>
#include <benchmark/benchmark.h>
#include <random>
#include <vector>

namespace {

enum Kind { General, NearRotation, SymmetricPD, Rank2 };

std::vector<Eigen::Matrix3d> matrices(Kind kind) {
  std::mt19937 rng(42);
  std::normal_distribution<double> n;
  auto random = [&] {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = n(rng);
    return A;
  };
  std::vector<Eigen::Matrix3d> out(1024);
  for (Eigen::Matrix3d& S : out) {
    const Eigen::Matrix3d A = random();
    switch (kind) {
    case General:
      S = A;
      break;
    case NearRotation: {
      Eigen::HouseholderQR<Eigen::Matrix3d> qr(A);
      Eigen::Matrix3d Q = qr.householderQ();
      if (Q.determinant() < 0) Q.col(0) = -Q.col(0);
      S = Q * (Eigen::Matrix3d::Identity() + 0.05 * random());
      break;
    }
    case SymmetricPD:
      S = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();
      break;
    case Rank2:
      S = A.col(0) * A.col(1).transpose() + A.col(2) * random().col(0).transpose();
      break;
    }
  }
  return out;
}

void BM_PolarRotation(benchmark::State& state) {
  const auto S = matrices(static_cast<Kind>(state.range(0)));
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(iarap::polar_rotation(S[i++ & 1023]));
  }
  state.SetItemsProcessed(state.iterations());
}

// Guesses for polar_rotation_near: the optimal rotation of S turned by 0.02 rad about a random axis, the
// guess a local step has in the middle of an ARAP solve (its rotations move by about that much per
// iteration).
std::vector<Eigen::Matrix3d> nearby_guesses(const std::vector<Eigen::Matrix3d>& S) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n;
  std::vector<Eigen::Matrix3d> guess(S.size());
  for (size_t i = 0; i < S.size(); ++i) {
    const Eigen::Vector3d axis = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
    guess[i] = iarap::polar_rotation(S[i]) * Eigen::AngleAxisd(0.02, axis).toRotationMatrix();
  }
  return guess;
}

void BM_PolarRotationNear(benchmark::State& state) {
  const auto S = matrices(static_cast<Kind>(state.range(0)));
  const auto guess = nearby_guesses(S);
  size_t i = 0;
  for (auto _ : state) {
    const size_t k = i++ & 1023;
    benchmark::DoNotOptimize(iarap::polar_rotation_near(S[k], guess[k]));
  }
  state.SetItemsProcessed(state.iterations());
}

// The same fits through the batched overload (four in lockstep), as the local step calls it; per fit.
void BM_PolarRotationNearBatch(benchmark::State& state) {
  const auto S = matrices(static_cast<Kind>(state.range(0)));
  const auto guess = nearby_guesses(S);
  std::vector<Eigen::Matrix3d> R(S.size());
  for (auto _ : state) {
    iarap::polar_rotation_near(S.data(), guess.data(), R.data(), static_cast<int>(S.size()));
    benchmark::DoNotOptimize(R.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(S.size()));
}

void BM_JacobiSvdRotation(benchmark::State& state) {
  const auto S = matrices(static_cast<Kind>(state.range(0)));
  size_t i = 0;
  for (auto _ : state) {
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(S[i++ & 1023], Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d U = svd.matrixU();
    if (U.determinant() * svd.matrixV().determinant() < 0) U.col(2) = -U.col(2);
    benchmark::DoNotOptimize(Eigen::Matrix3d(U * svd.matrixV().transpose()));
  }
  state.SetItemsProcessed(state.iterations());
}

void kinds(benchmark::internal::Benchmark* b) {
  b->ArgName("kind(0=general,1=near-rotation,2=spd,3=rank2)");
  for (int k = 0; k < 4; ++k) b->Arg(k);
}

} // namespace

BENCHMARK(BM_PolarRotation)->Apply(kinds);
BENCHMARK(BM_PolarRotationNear)->Apply(kinds);
BENCHMARK(BM_PolarRotationNearBatch)->Apply(kinds);
BENCHMARK(BM_JacobiSvdRotation)->Apply(kinds);
BENCHMARK_MAIN();
