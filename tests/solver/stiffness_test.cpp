// Per-vertex stiffness (issue 45, item 4): E = sum_i s_i E_i over the rotation cells, through
// ArapOptions::stiffness, for every method.
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <Eigen/SVD>

#include <limits>
#include <random>
#include <string>

namespace {

using namespace iarap;
using test::SolverMesh;

// Factors in [0.5, 4] from a fixed seed.
Eigen::VectorXd random_stiffness(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 4.0);
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) s(i) = u(rng);
  return s;
}

// A smooth deformation of the patch, off every rigid motion: a bend about the y axis plus a shear.
Eigen::MatrixXd bent(const Eigen::MatrixXd& V) {
  Eigen::MatrixXd U = V;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double a = 0.6 * V(i, 0);
    U(i, 0) = std::sin(a) / 0.6 + 0.1 * V(i, 1);
    U(i, 2) = V(i, 2) + (1 - std::cos(a)) / 0.6;
  }
  return U;
}

ArapOptions with(ArapMethod method, const Eigen::VectorXd& stiffness) {
  ArapOptions options;
  options.method = method;
  options.stiffness = stiffness;
  return options;
}

// The bunny with its bottom 10% along y at rest and its top 10% moved by `shift` diagonals along +x.
struct BunnyScene {
  SolverMesh m = test::bunny();
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

BunnyScene bunny_scene(double shift) {
  BunnyScene s;
  const Eigen::VectorXi bottom = test::to_vector(test::axis_band(s.m.V, 1, 0.1, -1));
  const Eigen::VectorXi top = test::to_vector(test::axis_band(s.m.V, 1, 0.1, +1));
  s.fixed.resize(bottom.size() + top.size());
  s.fixed << bottom, top;
  s.targets = test::rows_of(s.m.V, s.fixed);
  s.targets.bottomRows(top.size()).rowwise() += Eigen::RowVector3d(shift, 0, 0) * test::bbox_diagonal(s.m.V);
  return s;
}

// s = 1 everywhere is the energy without stiffness: the same factor and the same iterates, bit for bit
// (iARAP keeps its cotan-identity factorization).
TEST(Stiffness, OneEverywhereGivesTheSameBytes) {
  const BunnyScene scene = bunny_scene(0.1);
  const SolverMesh& m = scene.m;
  const Eigen::VectorXi& fixed = scene.fixed;
  const Eigen::MatrixXd& targets = scene.targets;
  ArapSolveOptions solve;
  solve.max_iterations = 10;
  solve.tolerance = 0;
  for (const ArapMethod method : test::kAllMethods) {
    ArapData plain = arap_precompute(m.V, m.F, fixed, with(method, Eigen::VectorXd()));
    ArapData ones = arap_precompute(m.V, m.F, fixed, with(method, Eigen::VectorXd::Ones(m.V.rows())));
    Eigen::MatrixXd U0 = m.V, U1 = m.V;
    arap_solve(plain, targets, U0, solve);
    arap_solve(ones, targets, U1, solve);
    EXPECT_TRUE(U0 == U1) << arap_method_name(method);
  }
}

// The rotations do not depend on s, so each cell's energy at any U is s_c times its energy without
// stiffness: one extra product per term, so agreement to a few ulps of the cell's energy (1e-13 relative
// leaves room for sums of a few dozen terms).
TEST(Stiffness, EachCellEnergyScalesByItsFactor) {
  const SolverMesh m = test::bumpy_patch(10);
  const Eigen::VectorXd s = random_stiffness(m.V.rows(), 5);
  const Eigen::MatrixXd U = bent(m.V);
  const Eigen::VectorXi fixed = Eigen::VectorXi::LinSpaced(3, 0, 2);
  for (const ArapMethod method : test::kAllMethods) {
    ArapOptions options = with(method, Eigen::VectorXd());
    options.intrinsic.refine_boundary = false; // cells = vertices, each with its own factor
    const Eigen::VectorXd e1 = arap_cell_energy(arap_precompute(m.V, m.F, fixed, options), U);
    options.stiffness = s;
    const Eigen::VectorXd es = arap_cell_energy(arap_precompute(m.V, m.F, fixed, options), U);
    ASSERT_EQ(es.size(), m.V.rows());
    for (Eigen::Index c = 0; c < es.size(); ++c)
      EXPECT_NEAR(es(c), s(c) * e1(c), 1e-13 * std::max(1e-12, std::abs(s(c) * e1(c))))
          << arap_method_name(method) << " cell " << c;
  }
}

// arap_gradient is the gradient of arap_energy with stiffness: central differences with step h have error
// O(h^2 |E'''|) + O(eps |E| / h); with h = 1e-5 (coordinates of order 1) both stay far below 1e-6 of the
// gradient's largest entry.
TEST(Stiffness, GradientMatchesFiniteDifferences) {
  const SolverMesh m = test::bumpy_patch(6);
  const Eigen::VectorXd s = random_stiffness(m.V.rows(), 9);
  const Eigen::MatrixXd U = bent(m.V);
  for (const ArapMethod method : test::kAllMethods) {
    const ArapData data = arap_precompute(m.V, m.F, Eigen::VectorXi::LinSpaced(3, 0, 2), with(method, s));
    const Eigen::MatrixXd g = arap_gradient(data, U);
    const double h = 1e-5, scale = g.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 1e-6);
    for (Eigen::Index i = 0; i < U.rows(); i += 5)
      for (int d = 0; d < 3; ++d) {
        Eigen::MatrixXd Up = U, Um = U;
        Up(i, d) += h;
        Um(i, d) -= h;
        const double fd = (arap_energy(data, Up) - arap_energy(data, Um)) / (2 * h);
        EXPECT_NEAR(g(i, d), fd, 1e-6 * scale) << arap_method_name(method) << " vertex " << i << " dim " << d;
      }
  }
}

// Original ARAP's element (i, j) has cells {i, j}: its entry of L is -(s_i + s_j) w_ij instead of -2 w_ij.
TEST(Stiffness, SystemMatrixWeighsEachEdgeByItsCells) {
  const SolverMesh m = test::lattice_patch(8);
  const Eigen::VectorXd s = random_stiffness(m.V.rows(), 2);
  const Eigen::VectorXi fixed = Eigen::VectorXi::LinSpaced(2, 0, 1);
  const Eigen::SparseMatrix<double> L1 =
      arap_system_matrix(arap_precompute(m.V, m.F, fixed, with(ArapMethod::Arap, Eigen::VectorXd())));
  const Eigen::SparseMatrix<double> Ls =
      arap_system_matrix(arap_precompute(m.V, m.F, fixed, with(ArapMethod::Arap, s)));
  int checked = 0;
  for (int k = 0; k < L1.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L1, k); it; ++it) {
      if (it.row() == it.col() || it.value() == 0.0) continue;
      const double want = it.value() * (s(it.row()) + s(it.col())) / 2;
      EXPECT_NEAR(Ls.coeff(it.row(), it.col()), want, 1e-14 * std::abs(want));
      ++checked;
    }
  EXPECT_GT(checked, 100);
}

// Largest distance of B's rows from the best rigid image of A's (Kabsch), rows centred.
double rigid_residual(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::MatrixXd a = A.rowwise() - A.colwise().mean(), b = B.rowwise() - B.colwise().mean();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(a.transpose() * b, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix3d R = svd.matrixU() * D * svd.matrixV().transpose();
  return (a * R - b).rowwise().norm().maxCoeff();
}

// A band across the middle of the bent bunny with stiffness 1e6 stays rigid (measured 7.9e-7 of the
// diagonal after 20 Newton iterations; the issue asks for 1e-4) while without it the band bends by over
// 1e-2 of the diagonal.
TEST(Stiffness, StiffBandStaysRigid) {
  const BunnyScene scene = bunny_scene(0.15);
  const SolverMesh& m = scene.m;
  const Eigen::VectorXi& fixed = scene.fixed;
  const Eigen::MatrixXd& targets = scene.targets;
  const double diagonal = test::bbox_diagonal(m.V);
  const double y0 = m.V.col(1).minCoeff(), y1 = m.V.col(1).maxCoeff();
  std::vector<int> band_list;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i)
    if (m.V(i, 1) > y0 + 0.45 * (y1 - y0) && m.V(i, 1) < y0 + 0.6 * (y1 - y0)) band_list.push_back(int(i));
  const Eigen::VectorXi band = test::to_vector(band_list);
  Eigen::VectorXd s = Eigen::VectorXd::Ones(m.V.rows());
  for (const int i : band_list) s(i) = 1e6;
  ArapSolveOptions solve; // Newton (the default), 20 iterations: measured 7.9e-7 with the band, 0.1 without
  solve.max_iterations = 20;
  for (const bool stiff : {false, true}) {
    ArapData data = arap_precompute(m.V, m.F, fixed, with(ArapMethod::Iarap, stiff ? s : Eigen::VectorXd()));
    Eigen::MatrixXd U = m.V;
    arap_solve(data, targets, U, solve);
    const double residual = rigid_residual(test::rows_of(m.V, band), test::rows_of(U, band)) / diagonal;
    if (stiff)
      EXPECT_LT(residual, 1e-4);
    else
      EXPECT_GT(residual, 1e-2);
  }
}

TEST(Stiffness, BadFactorsAreRefusedNamingTheVertex) {
  const SolverMesh m = test::bumpy_patch(4);
  const Eigen::VectorXi fixed = Eigen::VectorXi::LinSpaced(2, 0, 1);
  const auto message = [&](const Eigen::VectorXd& s) {
    try {
      arap_precompute(m.V, m.F, fixed, with(ArapMethod::Iarap, s));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(Eigen::VectorXd::Ones(3)).find("3 entries for a mesh of 25 vertices"), std::string::npos);
  for (const double bad : {0.0, -2.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    Eigen::VectorXd s = Eigen::VectorXd::Ones(m.V.rows());
    s(7) = bad;
    EXPECT_NE(message(s).find("stiffness of vertex 7"), std::string::npos) << bad;
  }
}

} // namespace
