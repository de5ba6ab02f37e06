// Volumetric ARAP (arap_tets.h): the energy against an independent sum over tetrahedra of
// vol |F - polar(F)|^2, rest states, and the engine's accelerators on a tet bar.
#include "iarap/core/errors.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_tets.h"
#include "tet_fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>
#include <iostream>
#include <random>
#include <utility>
#include <vector>

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

// A 10 x 2 x 2 bar (or `bar`, whose ends are at x = 0 and x = 10) with its x = 0 end fixed and its x = 10
// end turned by `degrees` about the bar's axis.
struct TwistScene {
  test::TetBar bar = test::tet_bar(10, 2, 2);
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

TwistScene twist_scene(double degrees, test::TetBar bar = test::tet_bar(10, 2, 2)) {
  TwistScene s;
  s.bar = std::move(bar);
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

// libigl's igl::arap_precomputation + igl::arap_solve with ARAP_ENERGY_TYPE_ELEMENTS on tetrahedra,
// re-derived densely from reading its source (arap.cpp, arap_linear_block_elements, cotangent.cpp for tets;
// docs/cli.md names the revisions): each tetrahedron t has one rotation R_t and weights c_ij = l_kl
// cot(theta_kl) / 6 on its six edges (l_kl, theta_kl the length and dihedral angle of the opposite edge),
// which here are computed as c_ij = -vol_t grad(phi_i) . grad(phi_j) (the same number: the off-diagonal of
// the linear element's stiffness, negated). One iteration, from U with the fixed rows at their targets: the
// covariances S_t = sum_{ij in t} c_ij (u_i - u_j)(v_i - v_j)^T, R_t = their closest rotations (SVD, the last
// singular vector flipped when det < 0, in double precision), then the free rows of -L U = K R, i.e. row i of
// sum_j L_ij (u_i - u_j) = sum_t sum_{j in t} c_ij R_t (v_i - v_j), with L_ij = sum_t c_ij.
Eigen::MatrixXd libigl_elements_arap(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                     const Eigen::VectorXi& fixed, const Eigen::MatrixXd& targets,
                                     Eigen::MatrixXd U, int iterations) {
  const Eigen::Index n = V.rows(), m = T.rows();
  std::vector<Eigen::Matrix4d> c(static_cast<size_t>(m)); // c(a, b) for the corners a != b of t
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);        // sum_t c_ij off the diagonal, -sum_j on it
  for (Eigen::Index t = 0; t < m; ++t) {
    Eigen::Matrix3d D; // rows: corners 1..3 less corner 0
    for (int a = 0; a < 3; ++a) D.row(a) = V.row(T(t, a + 1)) - V.row(T(t, 0));
    const double volume = std::abs(D.determinant()) / 6.0;
    Eigen::Matrix<double, 3, 4> grad; // grad(phi_a): D grad = e_a - e_0 differences
    grad.rightCols(3) = D.inverse();
    grad.col(0) = -grad.rightCols(3).rowwise().sum();
    Eigen::Matrix4d& ct = c[static_cast<size_t>(t)];
    ct = -volume * grad.transpose() * grad;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) {
          L(T(t, a), T(t, b)) += ct(a, b);
          L(T(t, a), T(t, a)) -= ct(a, b);
        }
  }
  std::vector<char> is_fixed(static_cast<size_t>(n), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) {
    is_fixed[static_cast<size_t>(fixed(k))] = 1;
    U.row(fixed(k)) = targets.row(k);
  }
  std::vector<Eigen::Index> free;
  for (Eigen::Index v = 0; v < n; ++v)
    if (!is_fixed[static_cast<size_t>(v)]) free.push_back(v);
  const auto nf = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd Lff(nf, nf);
  for (Eigen::Index a = 0; a < nf; ++a)
    for (Eigen::Index b = 0; b < nf; ++b) Lff(a, b) = -L(free[a], free[b]); // -L: positive definite
  const Eigen::LDLT<Eigen::MatrixXd> solver(Lff);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3); // K R
    for (Eigen::Index t = 0; t < m; ++t) {
      const Eigen::Matrix4d& ct = c[static_cast<size_t>(t)];
      Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          S += ct(a, b) * (U.row(T(t, a)) - U.row(T(t, b))).transpose() * (V.row(T(t, a)) - V.row(T(t, b)));
      Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::Matrix3d W = svd.matrixU();
      if ((svd.matrixU() * svd.matrixV().transpose()).determinant() < 0) W.col(2) *= -1.0;
      const Eigen::Matrix3d R = W * svd.matrixV().transpose();
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (a != b)
            rhs.row(T(t, a)) += ct(a, b) * (R * (V.row(T(t, a)) - V.row(T(t, b))).transpose()).transpose();
    }
    // -L_ff U_f = rhs_f + L_fc U_c
    Eigen::MatrixXd b(nf, 3);
    for (Eigen::Index a = 0; a < nf; ++a) {
      b.row(a) = rhs.row(free[a]);
      for (Eigen::Index k = 0; k < fixed.size(); ++k) b.row(a) += L(free[a], fixed(k)) * U.row(fixed(k));
    }
    const Eigen::MatrixXd x = solver.solve(b);
    for (Eigen::Index a = 0; a < nf; ++a) U.row(free[a]) = x.row(a);
  }
  return U;
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
  std::cout << "twisted bar, gradient to 1e-6: plain " << iterations[0] << ", Newton " << iterations[1]
            << "\n";
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

namespace {

// 20 plain iterations of iarap's tet energy are libigl's 20 (the reference above) from the same start, on
// the twisted bar and on a jittered one (obtuse dihedral angles: negative weights, which neither clamps):
// the same iterates up to rounding, which the contraction keeps at ~1e-14 of the diagonal; 1e-9 is the
// issue's bound. The start is not the rest shape (its free rows moved by a shear), so the first local
// step already differs from the identity.
TEST(TetArap, TwentyPlainIterationsAreLibiglsElementsArap) {
  const TwistScene twisted = twist_scene(60.0);
  test::TetBar bar = test::tet_bar(10, 2, 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Eigen::Index v = 0; v < bar.V.rows(); ++v)
    for (int d = 1; d < 3; ++d) bar.V(v, d) += u(rng); // x kept: the ends stay the fixed sets
  const TwistScene jittered = twist_scene(30.0, bar);
  for (const TwistScene* s : {&twisted, &jittered}) {
    const Eigen::MatrixXd& V = s->bar.V;
    ArapData data = arap_precompute_tets(V, s->bar.T, s->fixed);
    Eigen::MatrixXd start = V;
    for (Eigen::Index v = 0; v < V.rows(); ++v) start(v, 1) += 0.05 * V(v, 0); // a shear
    const Eigen::MatrixXd expected = libigl_elements_arap(V, s->bar.T, s->fixed, s->targets, start, 20);
    Eigen::MatrixXd U = start;
    ArapSolveOptions options;
    options.accelerator = ArapAccelerator::None;
    options.max_iterations = 20;
    options.tolerance = -1;
    const ArapReport report = arap_solve(data, s->targets, U, options);
    ASSERT_EQ(report.iterations, 20);
    const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
    const double distance = (U - expected).rowwise().norm().maxCoeff();
    EXPECT_LE(distance, 1e-9 * diagonal);
    EXPECT_GT((U - start).rowwise().norm().maxCoeff(), 0.1 * diagonal); // it did move
    std::cout << (s == &twisted ? "twisted" : "jittered") << " bar: 20 plain iterations vs libigl's, max "
              << distance / diagonal << " of the diagonal\n";
  }
}

} // namespace
