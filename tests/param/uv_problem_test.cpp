// The UV problem the engine's optimizers run on (src/param/uv_problem.h): its gradient is the derivative of
// its energy and its Hessian product the derivative of its gradient (central differences), for the
// per-triangle and the per-vertex energies, with the injectivity barrier felt by every triangle; and its
// plain step is the global step when flips are allowed.
#include "iarap/param/disk_mesh.h"
#include "iarap/param/lscm.h"
#include "iarap/param/triangle_frames.h"
#include "param/disk_meshes.h"
#include "param/uv_problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace iarap {
namespace {

struct Case {
  ParamEnergy energy;
  bool barrier;
};

// A cap of a sphere (curved, so no map is an isometry and every term is non-trivial), LSCM's map of it
// moved a little at random so that the rotations are far from the identity nowhere in particular.
class UvProblemTest : public ::testing::TestWithParam<Case> {
protected:
  void SetUp() override {
    const test::TestMesh cap = test::spherical_cap(4, 12, 0.45 * M_PI);
    disk_ = prepare_disk(cap.V, cap.F);
    U_ = lscm(disk_);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (Eigen::Index i = 0; i < U_.size(); ++i) U_.data()[i] += jitter(random);
    std::optional<param_detail::InjectivityBarrier> barrier;
    // Threshold 4: every triangle (det J near 1) is inside the barrier's range, so its terms are tested.
    if (GetParam().barrier) barrier.emplace(disk_, 0.1, 4.0, 0.8, face_jacobians(disk_.frames, disk_.F, U_));
    problem_ = std::make_unique<param_detail::UvProblem>(
        disk_, param_detail::make_uv_elastic_energy(disk_, GetParam().energy),
        std::vector<int>{disk_.boundary[0]}, std::move(barrier), U_);
    std::normal_distribution<double> normal;
    v_.resize(problem_->free_count(), 2);
    for (Eigen::Index i = 0; i < v_.size(); ++i) v_.data()[i] = normal(random);
  }

  double energy_at(const Eigen::MatrixXd& x) {
    problem_->set_positions(x);
    return problem_->local_step();
  }

  Eigen::MatrixXd gradient_at(const Eigen::MatrixXd& x) {
    energy_at(x);
    problem_->assemble_rhs();
    return problem_->gradient();
  }

  DiskMesh disk_;
  Eigen::MatrixXd U_, v_;
  std::unique_ptr<param_detail::UvProblem> problem_;
};

TEST_P(UvProblemTest, GradientIsTheEnergysDerivative) {
  const Eigen::MatrixXd x = problem_->positions();
  const double slope = (gradient_at(x).array() * v_.array()).sum();
  const double h = 1e-5;
  const double difference = (energy_at(x + h * v_) - energy_at(x - h * v_)) / (2 * h);
  // Central differences: O(h^2) truncation and O(eps E / h) rounding, both below 1e-7 of the slope here.
  EXPECT_NEAR(difference, slope, 1e-6 * std::abs(slope));
}

TEST_P(UvProblemTest, HessianProductIsTheGradientsDerivative) {
  const Eigen::MatrixXd x = problem_->positions();
  energy_at(x);
  problem_->prepare_hessian();
  const Eigen::MatrixXd Hv = problem_->hessian_product(v_);
  const double h = 1e-5;
  const Eigen::MatrixXd difference = (gradient_at(x + h * v_) - gradient_at(x - h * v_)) / (2 * h);
  EXPECT_LT((difference - Hv).norm(), 1e-6 * Hv.norm());
}

INSTANTIATE_TEST_SUITE_P(EnergiesAndBarrier, UvProblemTest,
                         ::testing::Values(Case{ParamEnergy::Triangle, false},
                                           Case{ParamEnergy::Triangle, true}, Case{ParamEnergy::Arap, false},
                                           Case{ParamEnergy::Iarap, true}),
                         [](const auto& test_info) {
                           return param_energy_name(test_info.param.energy) +
                                  (test_info.param.barrier ? "_barrier" : "");
                         });

// With flips allowed the plain step is the global step: M_ff x = r_f - M_fc U_c at fixed rotations, so
// the gradient at fixed rotations, 2 (M U - r(R)), vanishes at the free rows of the new map.
TEST(UvProblem, PlainStepSolvesTheGlobalSystem) {
  const test::TestMesh cap = test::spherical_cap(4, 12, 0.45 * M_PI);
  const DiskMesh disk = prepare_disk(cap.V, cap.F);
  Eigen::MatrixXd U = lscm(disk);
  auto energy = param_detail::make_uv_elastic_energy(disk, ParamEnergy::Triangle);
  const param_detail::UvElasticEnergy& term = *energy;
  param_detail::UvProblem problem(disk, std::move(energy), {disk.boundary[0]}, std::nullopt, U);
  problem.local_step();
  problem.assemble_rhs();
  Eigen::MatrixXd J, S, r;
  face_jacobians(disk.frames, disk.F, U, J);
  term.covariances(U, J, S);
  Eigen::MatrixXd R(S.rows(), 4);
  for (Eigen::Index c = 0; c < S.rows(); ++c) {
    const double a = S(c, 0) + S(c, 3), b = S(c, 2) - S(c, 1), n = std::hypot(a, b);
    R.row(c) << a / n, -b / n, b / n, a / n;
  }
  problem.set_positions(problem.plain_step());
  term.scatter(R, r);
  const Eigen::MatrixXd residual = term.system() * U - r;
  double largest = 0;
  for (Eigen::Index v = 0; v < U.rows(); ++v)
    if (v != disk.boundary[0]) largest = std::max(largest, residual.row(v).norm());
  EXPECT_LT(largest, 1e-12 * r.norm());
}

} // namespace
} // namespace iarap
