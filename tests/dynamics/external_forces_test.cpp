// External forces as a linear term of arap_solve (ArapSolveOptions::forces): statics under gravity.
#include "dynamics_fixtures.h"

#include "iarap/core/errors.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/solver/arap.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace iarap::test {
namespace {

class ExternalForcesTest : public SingleThreadTest {};

ArapSolveOptions tight(ArapAccelerator accelerator) {
  ArapSolveOptions options;
  options.max_iterations = 2000;
  options.tolerance = -1;            // run to the gradient rule
  options.gradient_tolerance = 1e-9; // of the initial gradient (that of gravity at rest)
  options.accelerator = accelerator;
  return options;
}

TEST_F(ExternalForcesTest, EquilibriumBalancesGravityForEveryAccelerator) {
  const HeldPatch p = held_patch(12);
  ArapData data = arap_precompute(p.mesh.V, p.mesh.F, p.fixed);
  const Eigen::VectorXd m = arap_vertex_masses(p.mesh.V, p.mesh.F, ArapMethod::Iarap);
  const Eigen::MatrixXd f = gravity_forces(m, Eigen::Vector3d(0, 0, -1));
  Eigen::MatrixXd reference;
  for (ArapAccelerator a :
       {ArapAccelerator::None, ArapAccelerator::Anderson, ArapAccelerator::Lbfgs, ArapAccelerator::Newton}) {
    SCOPED_TRACE(arap_accelerator_name(a));
    ArapSolveOptions options = tight(a);
    options.forces = f;
    Eigen::MatrixXd U = p.mesh.V;
    const ArapReport report = arap_solve(data, p.targets, U, options);
    EXPECT_EQ(report.stop_reason, ArapStopReason::GradientTolerance);
    // Stationarity of E_ARAP - f . U: dE/dU = f at every free vertex (the sign of the linear term). The
    // gradient rule stops at 1e-9 of |f| (the initial gradient), so the residual is below 1e-8 |f|.
    const Eigen::MatrixXd residual = arap_gradient(data, U) - f;
    double worst = 0;
    for (Eigen::Index i = 0; i < data.free.size(); ++i)
      worst = std::max(worst, residual.row(data.free(i)).norm());
    EXPECT_LT(worst, 1e-8 * f.norm());
    // The sag is visible: gravity pulls the free end down by a good part of the patch.
    const double sag = (p.mesh.V.col(2) - U.col(2)).maxCoeff();
    EXPECT_GT(sag, 0.05 * p.diagonal);
    // The reported parts: potential = -f . (U - V), arap_energy = E_ARAP(U), and the total decreased below 0
    // (the rest shape has total 0; the equilibrium is lower).
    EXPECT_NEAR(report.potential, -f.cwiseProduct(U - p.mesh.V).sum(), 1e-12 * std::abs(report.potential));
    EXPECT_NEAR(report.arap_energy, arap_energy(data, U), 1e-9 * report.arap_energy);
    EXPECT_LT(report.energies.back(), 0.0);
    if (reference.size() == 0)
      reference = U;
    else // one minimum, reached by all: within the gradient rule's reach (1e-9 |g_0| over L_ff's scale)
      EXPECT_LT((U - reference).rowwise().norm().maxCoeff(), 1e-6 * p.diagonal);
  }
}

TEST_F(ExternalForcesTest, PlainIterationNeverIncreasesTheTotalEnergy) {
  const HeldPatch p = held_patch(12);
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    SCOPED_TRACE(arap_method_name(method));
    ArapOptions arap;
    arap.method = method;
    ArapData data = arap_precompute(p.mesh.V, p.mesh.F, p.fixed, arap);
    ArapSolveOptions options;
    options.accelerator = ArapAccelerator::None;
    options.max_iterations = 200;
    options.tolerance = -1;
    options.forces =
        gravity_forces(arap_vertex_masses(p.mesh.V, p.mesh.F, method), Eigen::Vector3d(0, 0, -1));
    Eigen::MatrixXd U = p.mesh.V;
    const ArapReport report = arap_solve(data, p.targets, U, options);
    // Block descent on a quadratic in U (for fixed R) and an exact fit of R (for fixed U): each half-step
    // minimizes exactly, so only rounding can raise the energy (1e-13 of its size).
    double previous = report.initial_energy;
    for (double e : report.energies) {
      EXPECT_LE(e, previous + 1e-13 * std::abs(previous));
      previous = e;
    }
  }
}

TEST_F(ExternalForcesTest, ZeroForcesAreBitForBitNoForces) {
  const HeldPatch p = held_patch(8);
  ArapData data = arap_precompute(p.mesh.V, p.mesh.F, p.fixed);
  Eigen::MatrixXd targets = p.targets;
  targets.col(2).array() += 0.2;
  Eigen::MatrixXd U0 = p.mesh.V, U1 = p.mesh.V;
  arap_solve(data, targets, U0);
  ArapSolveOptions options;
  options.forces = Eigen::MatrixXd::Zero(p.mesh.V.rows(), 3);
  arap_solve(data, targets, U1, options);
  // Adding +0.0 and subtracting f . (U - V) = 0 change no bit of the iterates.
  EXPECT_EQ((U0 - U1).cwiseAbs().maxCoeff(), 0.0);
}

TEST_F(ExternalForcesTest, BadForcesAreRefused) {
  const HeldPatch p = held_patch(6);
  ArapData data = arap_precompute(p.mesh.V, p.mesh.F, p.fixed);
  Eigen::MatrixXd U = p.mesh.V;
  ArapSolveOptions options;
  options.forces = Eigen::MatrixXd::Zero(p.mesh.V.rows() - 1, 3);
  EXPECT_THROW(arap_solve(data, p.targets, U, options), InputError);
  options.forces = Eigen::MatrixXd::Zero(p.mesh.V.rows(), 3);
  options.forces(5, 1) = std::nan("");
  try {
    arap_solve(data, p.targets, U, options);
    FAIL() << "NaN force accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("forces row 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(arap_vertex_masses(p.mesh.V, p.mesh.F, ArapMethod::Iarap, 0.0), InputError);
  EXPECT_THROW(arap_vertex_masses(p.mesh.V, p.mesh.F, ArapMethod::Iarap, std::nan("")), InputError);
  EXPECT_THROW(gravity_forces(Eigen::VectorXd::Ones(3), Eigen::Vector3d(0, std::nan(""), 0)), InputError);
}

TEST_F(ExternalForcesTest, MassesAreDensityTimesArea) {
  const HeldPatch p = held_patch(10);
  double area = 0;
  for (Eigen::Index f = 0; f < p.mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = p.mesh.V.row(p.mesh.F(f, 0)), b = p.mesh.V.row(p.mesh.F(f, 1)),
                          c = p.mesh.V.row(p.mesh.F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    const Eigen::VectorXd m = arap_vertex_masses(p.mesh.V, p.mesh.F, method, 2.5);
    // Voronoi cells (intrinsic or not) partition the surface: the masses sum to density x area.
    EXPECT_NEAR(m.sum(), 2.5 * area, 1e-12 * area);
    EXPECT_GT(m.minCoeff(), 0.0);
  }
}

} // namespace
} // namespace iarap::test
