// Planar ARAP: a mesh given as #V x 2 (or x 3 in the plane with ArapOptions::planar) deforms in its plane
// with rotations about z. Checked against the 3D solver on the same mesh embedded at z = 0, which has the
// same minimizers wherever no cell is squeezed through a reflection.
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/polar_rotation.h"
#include "intrinsic/mesh_generators.h"
#include "solver_fixtures.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace iarap {
namespace {

constexpr ArapAccelerator kAccelerators[] = {ArapAccelerator::None, ArapAccelerator::Anderson,
                                             ArapAccelerator::Lbfgs, ArapAccelerator::Newton};

class PlanarArap : public test::SingleThreadTest {};

// The grid's left column fixed, its right column turned by `degrees` about the grid's centre and moved by
// (0.05, 0.02): for 10 degrees a bend in the plane that squeezes no cell through a reflection on the way
// (where one is, the solver in space turns it over and the two iterations part: see below).
struct PlanarScene {
  Eigen::MatrixXd V2; // #V x 2
  Eigen::MatrixXi F;
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets2; // #fixed x 2
};

PlanarScene bend(const test::TestMesh& m, double degrees) {
  PlanarScene s;
  s.V2 = m.V.leftCols(2);
  s.F = m.F;
  std::vector<int> fixed;
  for (Eigen::Index v = 0; v < s.V2.rows(); ++v)
    if (s.V2(v, 0) < 1e-9 || s.V2(v, 0) > 1 - 1e-9) fixed.push_back(static_cast<int>(v));
  s.fixed = test::to_vector(fixed);
  const double a = degrees * 3.14159265358979323846 / 180.0;
  Eigen::Matrix2d R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  s.targets2.resize(s.fixed.size(), 2);
  for (Eigen::Index k = 0; k < s.fixed.size(); ++k) {
    const Eigen::Vector2d p = s.V2.row(s.fixed(k)).transpose();
    const Eigen::Vector2d centre(0.5, 0.5), shift(0.05, 0.02);
    const Eigen::Vector2d target = p.x() < 0.5 ? p : Eigen::Vector2d(R * (p - centre) + centre + shift);
    s.targets2.row(k) = target.transpose();
  }
  return s;
}

Eigen::MatrixXd at_z0(const Eigen::MatrixXd& X2) {
  Eigen::MatrixXd X3 = Eigen::MatrixXd::Zero(X2.rows(), 3);
  X3.leftCols(2) = X2;
  return X3;
}

ArapOptions planar_options_for(ArapMethod method, bool planar = false) {
  ArapOptions o;
  o.method = method;
  o.planar = planar;
  return o;
}

// Both solvers run the same 25 iterations (no stopping rule, so rounding cannot stop one a step earlier).
// They differ by rounding alone: the planar rotation is closed-form, the 3D one a Newton iteration, each
// ~1e-16 relative per cell. Measured: below 7e-14 of the diagonal, except L-BFGS on the flipped grid's
// iARAP, 4.7e-13 (its line search and curvature test branch on differences of energies, which amplifies
// rounding); 1e-12 is the bound.
ArapSolveOptions fixed_iterations(ArapAccelerator accelerator) {
  ArapSolveOptions o;
  o.max_iterations = 25;
  o.tolerance = -1;
  o.accelerator = accelerator;
  return o;
}

void expect_planar_equals_embedded(const PlanarScene& s, const std::string& name, bool delaunay) {
  const double diagonal = test::bbox_diagonal(at_z0(s.V2));
  for (ArapMethod method : test::kAllMethods)
    for (ArapAccelerator accelerator : kAccelerators) {
      const std::string what =
          name + ", " + arap_method_name(method) + ", " + arap_accelerator_name(accelerator);
      ArapData planar = arap_precompute(s.V2, s.F, s.fixed, planar_options_for(method));
      ASSERT_TRUE(planar.planar) << what;
      Eigen::MatrixXd U2 = s.V2;
      arap_solve(planar, s.targets2, U2, fixed_iterations(accelerator));
      ASSERT_EQ(U2.cols(), 2) << what;

      ArapData space = arap_precompute(at_z0(s.V2), s.F, s.fixed, planar_options_for(method));
      ASSERT_FALSE(space.planar) << what;
      Eigen::MatrixXd U3 = at_z0(s.V2);
      arap_solve(space, at_z0(s.targets2), U3, fixed_iterations(accelerator));
      int turned_over = 0; // cells the solver in space fitted a rotation that turns the plane over
      for (const Eigen::Matrix3d& R : arap_rotations(space)) turned_over += R(2, 2) < 0 ? 1 : 0;
      if (method == ArapMethod::Arap && !delaunay) {
        // Original ARAP's negative weights make covariances indefinite: in space some cells turn over
        // (measured: 21-22 of 81 on the flipped grid) and the result lands elsewhere (0.35 of the
        // diagonal); the planar solve keeps every rotation about z. Nothing to compare.
        EXPECT_GT(turned_over, 0) << what;
        continue;
      }
      EXPECT_EQ(turned_over, 0) << what;
      // The 2x2 and 3x3 rotation fits agree to rounding, which the accelerators' line searches and CG steps
      // carry over the fixed iterations: measured up to 7.6e-12 of the diagonal (spokes-and-rims, L-BFGS)
      // with OpenBLAS's factor, under 1e-12 with the reference BLAS's.
      EXPECT_LT((U2 - U3.leftCols(2)).cwiseAbs().maxCoeff(), 1e-10 * diagonal) << what;
      // It moved: the comparison is not between two rest states.
      EXPECT_GT((U2 - s.V2).cwiseAbs().maxCoeff(), 0.02 * diagonal) << what;

      // The same planar data solved in three columns: z stays exactly 0, the plane coordinates agree
      // with the two-column solve bit for bit.
      Eigen::MatrixXd W3 = at_z0(s.V2);
      arap_solve(planar, at_z0(s.targets2), W3, fixed_iterations(accelerator));
      EXPECT_TRUE((W3.col(2).array() == 0.0).all()) << what;
      EXPECT_EQ(W3.leftCols(2), U2) << what;
    }
}

TEST_F(PlanarArap, GridEqualsTheSolverInSpaceAtZeroHeight) {
  expect_planar_equals_embedded(bend(test::planar_grid(8), 10.0), "grid 8x8", true);
}

TEST_F(PlanarArap, NonDelaunayMeshEqualsTheSolverInSpaceAtZeroHeight) {
  test::TestMesh m = test::planar_grid(8, 0.25, 5);
  test::random_planar_flips(m, 30, 11);
  expect_planar_equals_embedded(bend(m, 10.0), "flipped grid", false);
}

// Where a cell is squeezed through a reflection (the right column dragged across the left one), the
// solver in space turns such cells over (a rotation with R(2,2) = -1), the planar one keeps every rotation
// about z, and its result stays in the plane.
TEST_F(PlanarArap, ReflectedCellsKeepRotationsAboutZ) {
  PlanarScene s = bend(test::planar_grid(6), 0.0);
  for (Eigen::Index k = 0; k < s.fixed.size(); ++k)
    if (s.V2(s.fixed(k), 0) > 0.5) s.targets2(k, 0) = -0.6; // right column to the far left
  for (ArapMethod method : test::kAllMethods) {
    const std::string what = arap_method_name(method);
    ArapData planar = arap_precompute(s.V2, s.F, s.fixed, planar_options_for(method));
    Eigen::MatrixXd U2 = s.V2;
    arap_solve(planar, s.targets2, U2, fixed_iterations(ArapAccelerator::None));
    EXPECT_TRUE(U2.allFinite()) << what;
    for (const Eigen::Matrix3d& R : arap_rotations(planar)) {
      EXPECT_EQ(R(2, 2), 1.0) << what;
      EXPECT_EQ(R(0, 2), 0.0) << what;
      EXPECT_EQ(R(2, 0), 0.0) << what;
      EXPECT_NEAR(R.determinant(), 1.0, 1e-12) << what;
    }
    ArapData space = arap_precompute(at_z0(s.V2), s.F, s.fixed, planar_options_for(method));
    Eigen::MatrixXd U3 = at_z0(s.V2);
    arap_solve(space, at_z0(s.targets2), U3, fixed_iterations(ArapAccelerator::None));
    int turned_over = 0;
    for (const Eigen::Matrix3d& R : arap_rotations(space)) turned_over += R(2, 2) < 0 ? 1 : 0;
    EXPECT_GT(turned_over, 0) << what << ": the scene no longer reflects any cell";
  }
}

TEST_F(PlanarArap, RestTargetsStayAtRestExactly) {
  test::TestMesh m = test::planar_grid(6, 0.2, 3);
  const PlanarScene s = bend(m, 0.0);
  Eigen::MatrixXd rest_targets(s.fixed.size(), 2);
  for (Eigen::Index k = 0; k < s.fixed.size(); ++k) rest_targets.row(k) = s.V2.row(s.fixed(k));
  for (ArapMethod method : test::kAllMethods) {
    ArapData data = arap_precompute(s.V2, s.F, s.fixed, planar_options_for(method));
    Eigen::MatrixXd U = s.V2;
    const ArapReport report = arap_solve(data, rest_targets, U);
    EXPECT_EQ(report.initial_energy, 0.0) << arap_method_name(method);
    EXPECT_LT((U - s.V2).cwiseAbs().maxCoeff(), 1e-14) << arap_method_name(method);
  }
}

TEST(PlanarRotation, IsTheClosestRotationAboutZ) {
  Eigen::Matrix3d S;
  S << 2.0, -0.5, 0.0, 0.7, 1.5, 0.0, 0.0, 0.0, 0.0;
  const Eigen::Matrix3d R = planar_rotation(S);
  // Among rotations about z by angle t, tr(R(t)^T S) = (S00 + S11) cos t + (S10 - S01) sin t: brute force.
  double best = -1e300, best_t = 0;
  for (int i = 0; i < 200000; ++i) {
    const double t = -3.14159265358979323846 + i * (2 * 3.14159265358979323846 / 200000);
    const double value = (S(0, 0) + S(1, 1)) * std::cos(t) + (S(1, 0) - S(0, 1)) * std::sin(t);
    if (value > best) best = value, best_t = t;
  }
  EXPECT_NEAR(std::atan2(R(1, 0), R(0, 0)), best_t, 4e-5); // the search's step is 3.1e-5
  EXPECT_EQ(R(2, 2), 1.0);
  // A reflected block keeps a rotation about z; polar_rotation turns the plane over instead.
  Eigen::Matrix3d flipped = Eigen::Matrix3d::Zero();
  flipped(0, 0) = 1.0, flipped(1, 1) = -0.5;
  EXPECT_EQ(planar_rotation(flipped)(2, 2), 1.0);
  EXPECT_LT(polar_rotation(flipped)(2, 2), 0.0);
}

TEST(PlanarArapInput, OutOfPlanePositionsAreNamed) {
  test::TestMesh m = test::planar_grid(3);
  const Eigen::VectorXi fixed = (Eigen::VectorXi(2) << 0, 15).finished();
  Eigen::MatrixXd V = m.V;
  V(5, 2) = 1e-3;
  try {
    arap_precompute(V, m.F, fixed, planar_options_for(ArapMethod::Arap, true));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 5 has z"), std::string::npos) << e.what();
  }
  ArapData data = arap_precompute(m.V.leftCols(2).eval(), m.F, fixed, planar_options_for(ArapMethod::Arap));
  Eigen::MatrixXd targets = Eigen::MatrixXd::Zero(2, 3);
  targets(1, 2) = 0.5;
  Eigen::MatrixXd U = m.V;
  try {
    arap_solve(data, targets, U);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("targets row 1 has z"), std::string::npos) << e.what();
  }
  Eigen::MatrixXd short_U = Eigen::MatrixXd::Zero(4, 2);
  EXPECT_THROW(arap_solve(data, targets.leftCols(2), short_U), InputError);
  // Two columns are for planar data only.
  ArapData space = arap_precompute(m.V, m.F, fixed, planar_options_for(ArapMethod::Arap));
  Eigen::MatrixXd U2 = m.V.leftCols(2);
  EXPECT_THROW(arap_solve(space, targets.leftCols(2), U2), InputError);
}

} // namespace
} // namespace iarap
