// Volumetric ARAP (arap_tets.h): the energy against an independent sum over tetrahedra of
// vol |F - polar(F)|^2, rest states, and the engine's accelerators on a tet bar.
#include "iarap/core/errors.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_tets.h"
#include "tet_fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>
#include <random>

namespace {

using namespace iarap;

// sum_t vol_t |F_t - R_t|^2 with F_t = D_t(U) D_t(V)^{-1} (edge matrices from corner 0) and R_t the closest
// rotation to F_t (SVD, the last singular vector flipped when det < 0): written without the elements.
double tet_energy_by_svd(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::MatrixXd& U) {
  double energy = 0.0;
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    Eigen::Matrix3d Dv, Du;
    for (int c = 0; c < 3; ++c) {
      Dv.col(c) = (V.row(T(t, c + 1)) - V.row(T(t, 0))).transpose();
      Du.col(c) = (U.row(T(t, c + 1)) - U.row(T(t, 0))).transpose();
    }
    const double volume = std::abs(Dv.determinant()) / 6.0;
    const Eigen::Matrix3d F = Du * Dv.inverse();
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d W = svd.matrixU();
    if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) W.col(2) *= -1.0;
    const Eigen::Matrix3d R = W * svd.matrixV().transpose();
    energy += volume * (F - R).squaredNorm();
  }
  return energy;
}

// The bar with small random moves of its vertices (obtuse dihedral angles, negative weights).
test::TetBar jittered_bar(unsigned seed) {
  test::TetBar bar = test::tet_bar(3, 2, 2);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Eigen::Index v = 0; v < bar.V.rows(); ++v)
    for (int d = 0; d < 3; ++d) bar.V(v, d) += u(rng);
  return bar;
}

// A 10 x 2 x 2 bar with its x = 0 end fixed and its x = 10 end turned by `degrees` about the bar's axis.
struct TwistScene {
  test::TetBar bar = test::tet_bar(10, 2, 2);
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

TwistScene twist_scene(double degrees) {
  TwistScene s;
  std::vector<int> ends;
  for (Eigen::Index v = 0; v < s.bar.V.rows(); ++v)
    if (s.bar.V(v, 0) == 0.0 || s.bar.V(v, 0) == 10.0) ends.push_back(static_cast<int>(v));
  s.fixed = Eigen::Map<Eigen::VectorXi>(ends.data(), static_cast<Eigen::Index>(ends.size()));
  s.targets.resize(s.fixed.size(), 3);
  const double a = degrees * M_PI / 180.0;
  for (Eigen::Index k = 0; k < s.fixed.size(); ++k) {
    Eigen::RowVector3d p = s.bar.V.row(s.fixed(k));
    if (p(0) == 10.0) {
      const double y = p(1) - 1.0, z = p(2) - 1.0;
      p(1) = 1.0 + std::cos(a) * y - std::sin(a) * z;
      p(2) = 1.0 + std::sin(a) * y + std::cos(a) * z;
    }
    s.targets.row(k) = p;
  }
  return s;
}

TEST(TetArap, EnergyIsTheSumOfVolumeTimesDistanceToTheClosestRotation) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const test::TetBar bar = jittered_bar(seed);
    const ArapData data = arap_precompute_tets(bar.V, bar.T, Eigen::VectorXi::Constant(1, 0));
    int negative = 0;
    for (Eigen::Index e = 0; e < data.elements.size(); ++e) negative += data.elements.w(e) < 0;
    std::mt19937 rng(seed + 10);
    std::normal_distribution<double> g(0.0, 0.3);
    Eigen::MatrixXd U = bar.V;
    for (Eigen::Index v = 0; v < U.rows(); ++v)
      for (int d = 0; d < 3; ++d) U(v, d) += g(rng) + 0.4 * bar.V(v, (d + 1) % 3);
    const double expected = tet_energy_by_svd(bar.V, bar.T, U);
    EXPECT_NEAR(arap_energy(data, U), expected, 1e-12 * expected)
        << "seed " << seed << ", " << negative << " negative weights";
    EXPECT_GT(negative, 0) << "the jitter should make some dihedral angles obtuse";
    EXPECT_NEAR(arap_energy(data, 2.0 * bar.V), tet_energy_by_svd(bar.V, bar.T, 2.0 * bar.V), 1e-12);
  }
}

TEST(TetArap, BoundaryFacesComponentsAndCells) {
  const test::TetBar bar = test::tet_bar(4, 2, 3);
  const ArapData data = arap_precompute_tets(bar.V, bar.T, Eigen::VectorXi::Constant(1, 0));
  EXPECT_EQ(data.F.rows(), 4 * (4 * 2 + 2 * 3 + 4 * 3)); // two triangles per boundary square
  EXPECT_EQ(data.component_count, 1);
  EXPECT_EQ(data.elements.num_cells, bar.T.rows());
  EXPECT_EQ(arap_rotations(data).size(), static_cast<size_t>(bar.T.rows()));
  // One tetrahedron has fewer cells than vertices: padded with empty cells, the solve still works.
  const Eigen::MatrixXd corners = (Eigen::MatrixXd(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished();
  const Eigen::MatrixXi one = (Eigen::MatrixXi(1, 4) << 0, 1, 2, 3).finished();
  ArapData single = arap_precompute_tets(corners, one, Eigen::VectorXi::Constant(1, 3));
  EXPECT_EQ(single.elements.num_cells, 4);
  Eigen::MatrixXd U = corners;
  U.row(0) << 0.1, 0.1, -0.2;
  const ArapReport report = arap_solve(single, corners.row(3), U);
  EXPECT_LT(report.arap_energy, 1e-20);
  for (int i = 0; i < 4; ++i) // only vertex 3 is held: the result is a rotation of the rest shape about it
    for (int j = 0; j < i; ++j)
      EXPECT_NEAR((U.row(i) - U.row(j)).norm(), (corners.row(i) - corners.row(j)).norm(), 1e-9);
}

TEST(TetArap, StaysAtRestUnderRestTargets) {
  TwistScene s = twist_scene(0.0);
  ArapData data = arap_precompute_tets(s.bar.V, s.bar.T, s.fixed);
  const double diagonal = (s.bar.V.colwise().maxCoeff() - s.bar.V.colwise().minCoeff()).norm();
  for (ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    Eigen::MatrixXd U = s.bar.V;
    ArapSolveOptions options;
    options.accelerator = accelerator;
    options.max_iterations = 50;
    options.tolerance = -1;
    arap_solve(data, s.targets, U, options);
    EXPECT_LE((U - s.bar.V).rowwise().norm().maxCoeff(), 1e-12 * diagonal)
        << arap_accelerator_name(accelerator);
  }
}

TEST(TetArap, NewtonConvergesInFewerIterationsThanPlainOnATwistedBar) {
  TwistScene s = twist_scene(60.0);
  ArapData data = arap_precompute_tets(s.bar.V, s.bar.T, s.fixed);
  int iterations[2] = {0, 0};
  Eigen::MatrixXd results[2];
  for (int k = 0; k < 2; ++k) {
    Eigen::MatrixXd U = s.bar.V;
    ArapSolveOptions options;
    options.accelerator = k == 0 ? ArapAccelerator::None : ArapAccelerator::Newton;
    options.gradient_tolerance = 1e-6;
    options.tolerance = -1;
    options.max_iterations = 20000;
    const ArapReport report = arap_solve(data, s.targets, U, options);
    ASSERT_TRUE(report.converged) << arap_accelerator_name(options.accelerator);
    EXPECT_EQ(report.stop_reason, ArapStopReason::GradientTolerance);
    iterations[k] = report.iterations;
    results[k] = U;
    // The gradient of the result, from the public function, vanishes at the free vertices.
    const Eigen::MatrixXd G = arap_gradient(data, U);
    double free_norm = 0.0;
    for (Eigen::Index f = 0; f < data.free.size(); ++f) free_norm += G.row(data.free(f)).squaredNorm();
    EXPECT_LE(std::sqrt(free_norm), 1e-5 * report.initial_gradient_norm);
  }
  EXPECT_GE(iterations[0], 5 * iterations[1]) << "plain " << iterations[0] << ", Newton " << iterations[1];
  EXPECT_LT((results[0] - results[1]).rowwise().norm().maxCoeff(), 1e-3);
}

TEST(TetArap, StiffnessScalesTetrahedraSoftPointsLieOnBoundaryFacesAndFixedSetsChange) {
  const test::TetBar bar = jittered_bar(4);
  const Eigen::VectorXi fixed = Eigen::VectorXi::Constant(1, 0);
  ArapOptions options;
  options.stiffness = Eigen::VectorXd::Constant(bar.V.rows(), 2.0);
  const ArapData stiff = arap_precompute_tets(bar.V, bar.T, fixed, options);
  const ArapData plain = arap_precompute_tets(bar.V, bar.T, fixed);
  const Eigen::MatrixXd U = 1.3 * bar.V + 0.1 * bar.V.rowwise().reverse();
  EXPECT_NEAR(arap_energy(stiff, U), 2.0 * arap_energy(plain, U), 1e-12 * arap_energy(plain, U));
  // A soft point at the centre of boundary face 0 pulled outward; vertex 0 held.
  ArapSoftConstraints soft;
  soft.faces = Eigen::VectorXi::Constant(1, 0);
  soft.barycentric = Eigen::RowVector3d::Constant(1.0 / 3.0);
  soft.face_weights = Eigen::VectorXd::Constant(1, 10.0);
  ArapData data = arap_precompute_tets(bar.V, bar.T, fixed, soft);
  ASSERT_EQ(data.F.rows(), tet_boundary_faces(bar.T).rows());
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  for (int k = 0; k < 3; ++k) centre += bar.V.row(data.F(0, k)) / 3.0;
  Eigen::MatrixXd X = bar.V;
  const ArapReport report = arap_solve(data, bar.V.row(0), centre + Eigen::RowVector3d(0.0, 0.0, 0.3), X);
  EXPECT_GT(report.penalty, 0.0);
  EXPECT_GT((X - bar.V).norm(), 0.05);
  // A new fixed set refactorizes; rest targets keep the rest shape.
  arap_set_fixed(data, Eigen::VectorXi::LinSpaced(3, 0, 2));
  Eigen::MatrixXd Y = bar.V;
  arap_solve(data, bar.V.topRows(3), centre, Y);
  EXPECT_LT((Y - bar.V).norm(), 1e-9);
}

TEST(TetArap, RefusesSurfaceMethodsAndBadTetrahedra) {
  const test::TetBar bar = test::tet_bar(1, 1, 1);
  ArapOptions options;
  options.method = ArapMethod::SpokesRims;
  EXPECT_THROW(arap_precompute_tets(bar.V, bar.T, Eigen::VectorXi::Constant(1, 0), options), InputError);
  Eigen::MatrixXd flat = bar.V;
  flat.col(2).setZero();
  try {
    arap_precompute_tets(flat, bar.T, Eigen::VectorXi::Constant(1, 0));
    ADD_FAILURE() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 0"), std::string::npos) << e.what();
  }
  Eigen::MatrixXi bad = bar.T;
  bad(3, 2) = 99;
  try {
    arap_precompute_tets(bar.V, bad, Eigen::VectorXi::Constant(1, 0));
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tetrahedron 3"), std::string::npos) << e.what();
  }
}

} // namespace
