// Accelerated local/global (issue 17): Anderson and L-BFGS against the plain iteration, on all three
// energies including iARAP's boundary-refined cells.
#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "intrinsic/mesh_generators.h"
#include "solver_fixtures.h"

#include "solver/local_global_problem.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

using namespace iarap;
using test::kPlainAndAccelerators;
using test::max_row_distance;
using test::SolverMesh;

const ArapAccelerator kAccelerators[] = {ArapAccelerator::Anderson, ArapAccelerator::Lbfgs,
                                         ArapAccelerator::Newton};

// A problem: mesh, energy, constrained set and targets.
struct Scene {
  std::string name;
  SolverMesh mesh;
  ArapOptions options;
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

// Bottom `fraction` along `axis` at rest, top `fraction` moved by `shift` (in diagonals) after turning
// `degrees` about z through its centroid: the "60-degree" edit when shift = (0.3, -0.1, 0).
Scene band_scene(const std::string& name, const SolverMesh& m, ArapMethod method, int axis, double degrees,
                 const Eigen::RowVector3d& shift, bool refine_boundary = true) {
  Scene s{name, m, {}, {}, {}};
  s.options.method = method;
  s.options.intrinsic.refine_boundary = refine_boundary;
  const std::vector<int> bottom = test::axis_band(m.V, axis, 0.1, -1),
                         top = test::axis_band(m.V, axis, 0.1, +1);
  s.fixed.resize(static_cast<Eigen::Index>(bottom.size() + top.size()));
  s.fixed << test::to_vector(bottom), test::to_vector(top);
  s.targets = test::rows_of(m.V, s.fixed);
  const auto n_bottom = static_cast<Eigen::Index>(bottom.size());
  const Eigen::MatrixXd handle = s.targets.bottomRows(s.fixed.size() - n_bottom);
  const Eigen::RowVector3d centroid = handle.colwise().mean();
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(degrees * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::RowVector3d t = shift * test::bbox_diagonal(m.V);
  s.targets.bottomRows(s.fixed.size() - n_bottom) =
      ((handle.rowwise() - centroid) * Q.transpose()).rowwise() + centroid + t;
  return s;
}

SolverMesh bent_obtuse_strip() {
  const test::TestMesh m = test::sheared_strip(16, 4, 2.0);
  return {m.V, m.F};
}

// Small problems of every kind: the three energies on a curved patch with boundary, original ARAP also on
// a Delaunay lattice (all weights positive), and iARAP with boundary-refined cells (more rotation cells
// than vertices).
std::vector<Scene> small_scenes() {
  const SolverMesh patch = test::bumpy_patch(9), lattice = test::lattice_patch(10),
                   strip = bent_obtuse_strip();
  const Eigen::RowVector3d shift(0.2, -0.1, 0.05);
  return {
      band_scene("arap lattice", lattice, ArapMethod::Arap, 1, 50, shift),
      band_scene("arap patch", patch, ArapMethod::Arap, 1, 50, shift),
      band_scene("spokes-rims patch", patch, ArapMethod::SpokesRims, 1, 50, shift),
      band_scene("iarap patch", patch, ArapMethod::Iarap, 1, 50, shift),
      band_scene("iarap refined strip", strip, ArapMethod::Iarap, 0, 40, Eigen::RowVector3d(-0.1, 0.1, 0.1))};
}

ArapSolveOptions accelerated(ArapAccelerator accelerator, int iterations, double tolerance = -1.0) {
  ArapSolveOptions options;
  options.accelerator = accelerator;
  options.max_iterations = iterations;
  options.tolerance = tolerance;
  return options;
}

// Today's plain loop written out with the public building blocks, as arap_solve ran it before issue 17.
std::vector<double> reference_plain_loop(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                                         int iterations) {
  for (Eigen::Index k = 0; k < data.fixed.size(); ++k) U.row(data.fixed(k)) = targets.row(k);
  Eigen::MatrixXd U_c(data.fixed.size() + data.pinned.size(), 3);
  U_c.topRows(data.fixed.size()) = targets;
  for (Eigen::Index k = 0; k < data.pinned.size(); ++k)
    U_c.row(data.fixed.size() + k) = U.row(data.pinned(k));
  const Eigen::MatrixXd Lfc_Uc = data.L_fc * U_c;
  ArapElements::ValueRows U_rows;
  Eigen::VectorXd cell_energy;
  Eigen::MatrixXd rhs, B(data.free.size(), 3);
  data.R.clear(); // arap_solve's first fit starts cold too
  std::vector<double> energies{fit_rotations(data.elements, U, U_rows, data.R, cell_energy)};
  for (int k = 0; k < iterations; ++k) {
    arap_rhs(data.elements, data.R, rhs);
    for (Eigen::Index i = 0; i < data.free.size(); ++i) B.row(i) = rhs.row(data.free(i)) - Lfc_Uc.row(i);
    const Eigen::MatrixXd X = data.solver.solve(B);
    for (Eigen::Index i = 0; i < data.free.size(); ++i) U.row(data.free(i)) = X.row(i);
    energies.push_back(fit_rotations(data.elements, U, U_rows, data.R, cell_energy));
  }
  return energies;
}

class AcceleratedSolve : public test::SingleThreadTest {}; // meshes of ~100 vertices

TEST_F(AcceleratedSolve, AcceleratorNamesRoundTrip) {
  for (ArapAccelerator a : kPlainAndAccelerators)
    EXPECT_EQ(parse_arap_accelerator(arap_accelerator_name(a)), a);
  try {
    parse_arap_accelerator("fast");
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'fast'"), std::string::npos) << e.what();
  }
}

// `--accel none` and window 0 must be today's iteration exactly: same operations in the same order, so
// equality is bitwise (EXPECT_EQ on doubles, no tolerance).
TEST_F(AcceleratedSolve, NoAcceleratorAndWindowZeroAreThePlainIterationBitForBit) {
  for (const Scene& s : small_scenes()) {
    ArapData reference_data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    Eigen::MatrixXd reference_U = s.mesh.V;
    const std::vector<double> reference = reference_plain_loop(reference_data, s.targets, reference_U, 12);
    for (int variant = 0; variant < 2; ++variant) {
      ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
      Eigen::MatrixXd U = s.mesh.V;
      ArapSolveOptions options =
          accelerated(variant == 0 ? ArapAccelerator::None : ArapAccelerator::Anderson, 12);
      options.window = variant == 0 ? 6 : 0;
      const ArapReport report = arap_solve(data, s.targets, U, options);
      EXPECT_EQ(report.accelerator, ArapAccelerator::None);
      ASSERT_EQ(report.energies.size(), 12u) << s.name;
      EXPECT_EQ(report.initial_energy, reference[0]) << s.name;
      for (size_t k = 0; k < 12; ++k)
        EXPECT_EQ(report.energies[k], reference[k + 1]) << s.name << " iteration " << k + 1;
      EXPECT_TRUE((U.array() == reference_U.array()).all()) << s.name;
      for (size_t c = 0; c < data.R.size(); ++c)
        EXPECT_TRUE((data.R[c].array() == reference_data.R[c].array()).all()) << s.name << " cell " << c;
    }
  }
}

// The safeguards keep the energy monotone. Anderson accepts an iterate only when E <= the last accepted
// energy (exact comparison) and L-BFGS only under Armijo (E < E_prev); their fallback is the plain step,
// which cannot increase E where every local and global step is a true minimization (positive weights,
// positive definite L_ff): 1e-12 relative covers its rounding. Original ARAP is tested on the Delaunay
// lattice only: with negative weights the plain step itself is not a descent step.
TEST_F(AcceleratedSolve, EnergyIsMonotone) {
  for (const Scene& s : small_scenes()) {
    if (s.name == "arap patch") continue;
    ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    for (ArapAccelerator a : kAccelerators) {
      Eigen::MatrixXd U = s.mesh.V;
      const ArapReport report = arap_solve(data, s.targets, U, accelerated(a, 60));
      double previous = report.initial_energy;
      for (size_t k = 0; k < report.energies.size(); ++k) {
        EXPECT_LE(report.energies[k], previous + 1e-12 * std::abs(previous))
            << s.name << " " << arap_accelerator_name(a) << " iteration " << k + 1;
        previous = report.energies[k];
      }
      EXPECT_NEAR(arap_energy(data, U), report.energies.back(), 1e-12 * std::abs(report.energies.back()));
      // Some accelerated iterates were taken (the test would otherwise only test the plain iteration).
      int taken = 0;
      for (unsigned char accepted : report.accepted) taken += accepted;
      EXPECT_GT(taken, 10) << s.name << " " << arap_accelerator_name(a);
    }
  }
}

// Both run to a gradient 1e-10 of the initial one land on the plain fixed point. Near a non-degenerate
// minimum x - x* ~ H^{-1} g, so 1e-10 of the initial gradient is ~1e-10 of the initial displacement
// (times the Hessian's condition relative to L_ff, small on these 100-vertex meshes): 1e-8 of the diagonal
// is the bound and leaves that margin.
TEST_F(AcceleratedSolve, AcceleratedAndPlainReachTheSameFixedPoint) {
  for (const Scene& s : small_scenes()) {
    ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    const double diag = test::bbox_diagonal(s.mesh.V);
    ArapSolveOptions plain = accelerated(ArapAccelerator::None, 20000);
    plain.gradient_tolerance = 1e-10;
    Eigen::MatrixXd U_plain = s.mesh.V;
    const ArapReport plain_report = arap_solve(data, s.targets, U_plain, plain);
    ASSERT_TRUE(plain_report.converged) << s.name;
    for (ArapAccelerator a : kAccelerators) {
      ArapSolveOptions options = accelerated(a, 2000);
      options.gradient_tolerance = 1e-10;
      Eigen::MatrixXd U = s.mesh.V;
      const ArapReport report = arap_solve(data, s.targets, U, options);
      ASSERT_TRUE(report.converged) << s.name << " " << arap_accelerator_name(a);
      EXPECT_LT(max_row_distance(U, U_plain), 1e-8 * diag) << s.name << " " << arap_accelerator_name(a);
      EXPECT_LT(report.iterations, plain_report.iterations) << s.name << " " << arap_accelerator_name(a);
      EXPECT_LE(report.gradient_norms.back(), 1e-10 * report.initial_gradient_norm);
    }
  }
}

// The default accelerator on the repo's bunny under the issue-17 edit (bend60: top 10% turned 60 degrees and
// moved by 0.3 diagonals), where the energies have several local minima and L-BFGS, for one, can end in
// another (docs/accelerators.md, "Several minima"): Newton must end where the plain iteration does. Both run
// to a 1e-9 relative gradient; at a non-degenerate minimum the distance left is ~ |H^-1| |g|, measured 2.9e-7
// (spokes-rims) and 3.0e-7 (iARAP) of the diagonal, while the other minimum Anderson ends in on iARAP here
// lies 3.4e-2 of the diagonal away: 1e-5 separates the two cases with wide margins. (Release only: under the
// sanitizers plain's 2400-2800 iterations take a minute.)
TEST_F(AcceleratedSolve, DefaultAcceleratorEndsWherePlainDoesOnTheBentBunny) {
  const MeshData m = read_mesh(test::data_path("bunny.off"));
  const ConstraintSet c = resolve_scenario(read_scenario(test::data_path("bend60_scenario.json")), m.V);
  const double diag = test::bbox_diagonal(m.V);
  for (ArapMethod method : {ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    ArapOptions arap_options;
    arap_options.method = method;
    ArapData data = arap_precompute(m.V, m.F, c.fixed, arap_options);
    ArapSolveOptions plain = accelerated(ArapAccelerator::None, 20000);
    plain.gradient_tolerance = 1e-9;
    Eigen::MatrixXd U_plain = m.V;
    ASSERT_TRUE(arap_solve(data, c.targets, U_plain, plain).converged) << arap_method_name(method);
    ArapSolveOptions options; // the defaults, Newton
    options.max_iterations = 200;
    options.tolerance = -1;
    options.gradient_tolerance = 1e-9;
    Eigen::MatrixXd U = m.V;
    const ArapReport report = arap_solve(data, c.targets, U, options);
    ASSERT_TRUE(report.converged) << arap_method_name(method);
    EXPECT_LT(max_row_distance(U, U_plain), 1e-5 * diag) << arap_method_name(method);
  }
}

// Newton run on past its minimum: once its predicted decrease reaches the energy's rounding, the energy
// cannot tell a good step from a bad one, and a raw achieved / predicted ratio (noise) rejected about every
// other step and shrank the trust radius towards zero (a 43K drag start: 2000 such iterations). Measured
// against the rounding level (newton_trust_region.cpp), 110 more iterations at the floor reject nothing
// more and keep the radius (rho near 1 grows it at most), and the energy stays within rounding (1e-12
// relative) of the minimum's.
TEST_F(AcceleratedSolve, NewtonAtItsMinimumKeepsItsRadius) {
  for (const Scene& s : small_scenes()) {
    ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    Eigen::MatrixXd U_short = s.mesh.V, U_long = s.mesh.V;
    ArapSolveOptions options = accelerated(ArapAccelerator::Newton, 40);
    const ArapReport at_minimum = arap_solve(data, s.targets, U_short, options);
    // At the minimum after 40 iterations: the gradient at rounding level (1e-9 leaves a wide margin).
    ASSERT_LT(at_minimum.gradient_norms.back(), 1e-9 * at_minimum.initial_gradient_norm) << s.name;
    options.max_iterations = 150;
    const ArapReport past = arap_solve(data, s.targets, U_long, options);
    EXPECT_EQ(past.rejected, at_minimum.rejected) << s.name;
    EXPECT_GE(past.newton_trust_radius, at_minimum.newton_trust_radius) << s.name;
    const double minimum = at_minimum.energies.back();
    for (size_t k = 40; k < past.energies.size(); ++k)
      EXPECT_NEAR(past.energies[k], minimum, 1e-12 * minimum) << s.name << " iteration " << k + 1;
  }
}

// The reported gradient norm is that of Eq. 14 at the returned U's free rows, computed independently by
// arap_gradient; both sum the same terms in another order, so they agree to rounding (1e-9 relative).
TEST_F(AcceleratedSolve, ReportedGradientNormIsTheGradientAtTheResult) {
  const Scene s = small_scenes()[3];
  ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
  for (ArapAccelerator a : kPlainAndAccelerators) {
    Eigen::MatrixXd U = s.mesh.V;
    const ArapReport report = arap_solve(data, s.targets, U, accelerated(a, 7));
    const Eigen::MatrixXd g = arap_gradient(data, U);
    double squared = 0;
    for (Eigen::Index i = 0; i < data.free.size(); ++i) squared += g.row(data.free(i)).squaredNorm();
    EXPECT_NEAR(report.gradient_norms.back(), std::sqrt(squared), 1e-9 * std::sqrt(squared))
        << arap_accelerator_name(a);
    EXPECT_EQ(report.gradient_norms.size(), 7u);
    EXPECT_EQ(report.accepted.size(), 7u);
    EXPECT_EQ(report.elapsed_ms.size(), 7u);
  }
}

// After `iterations` iterations of `accelerator` on the bunny whose bottom and top 10% are moved rigidly:
// the distance to the rigidly moved bunny, in bbox diagonals.
double rigid_motion_distance(ArapMethod method, ArapAccelerator accelerator, int iterations) {
  const SolverMesh m = test::bunny();
  const double diag = test::bbox_diagonal(m.V);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::MatrixXd moved = (m.V * Q.transpose()).rowwise() + Eigen::RowVector3d(0.3, -0.2, 0.1) * diag;
  const Scene s = band_scene("rigid", m, method, 1, 0, Eigen::RowVector3d::Zero());
  ArapData data = arap_precompute(m.V, m.F, s.fixed, s.options);
  Eigen::MatrixXd U = m.V;
  const ArapReport report =
      arap_solve(data, test::rows_of(moved, s.fixed), U, accelerated(accelerator, iterations));
  EXPECT_LE(report.iterations, iterations);
  return max_row_distance(U, moved) / diag;
}

// A rigid motion of the constraints (0.7 rad about z and a translation of (0.3, -0.2, 0.1) diagonals, bottom
// and top 10% moved): the rigidly moved bunny is the minimizer with zero energy. Measured distances to it
// (bbox diagonals) after 30 / 60 iterations: plain 1.9e-2 / -, Anderson (window 6; the default is 8 now)
// 4.7e-5 / 3.3e-8 (spokes-rims) and 1.6e-4 / 4.6e-8 (iARAP); L-BFGS 2.1e-4 / 1.2e-6. Issue 17 asks for 1e-7
// within 30 iterations; Anderson gets there within 60 (plain needs over 300 for 1e-5), which this test holds.
TEST_F(AcceleratedSolve, RigidMotionWithinSixtyIterations) {
  for (ArapMethod method : {ArapMethod::SpokesRims, ArapMethod::Iarap})
    EXPECT_LT(rigid_motion_distance(method, ArapAccelerator::Anderson, 60), 1e-7) << arap_method_name(method);
}

// Newton's Hessian product is the derivative of the gradient g(x) = L_ff x - B(R*(x)): central differences
// of g along a random v at a deformed state (all energies, the refined strip's extra cells included). Their
// error is O(h^2 |g'''|) + O(eps |g| / h): measured to fall 100x per 10x smaller h down to h = 1e-6 of the
// diagonal, where it is 1e-8 (original ARAP's patch, a nearly degenerate cell) to 1e-10 of |H v|; 1e-6 is a
// wide margin that a wrong sign, factor or transpose (errors of order 1) cannot pass.
TEST_F(AcceleratedSolve, HessianProductIsTheDerivativeOfTheGradient) {
  for (const Scene& s : small_scenes()) {
    ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    Eigen::MatrixXd U = s.mesh.V;
    arap_solve(data, s.targets, U, accelerated(ArapAccelerator::None, 5)); // a deformed, unconverged state
    detail::LocalGlobalProblem problem(data, s.targets, U);
    const Eigen::MatrixXd x = problem.positions();
    const auto gradient_at = [&](const Eigen::MatrixXd& y) {
      problem.set_positions(y);
      problem.local_step();
      problem.assemble_rhs();
      return problem.gradient();
    };
    gradient_at(x);
    problem.prepare_hessian();
    std::srand(7);
    const Eigen::MatrixXd v = Eigen::MatrixXd::Random(x.rows(), 3);
    const Eigen::MatrixXd Hv = problem.hessian_product(v);
    const double h = 1e-6 * test::bbox_diagonal(s.mesh.V); // |v_ij| <= 1
    const Eigen::MatrixXd fd = (gradient_at(x + h * v) - gradient_at(x - h * v)) / (2 * h);
    EXPECT_LT((Hv - fd).norm(), 1e-6 * Hv.norm()) << s.name;
    // The rotation term matters: L_ff v alone (the gradient's change with the rotations frozen) is off by
    // far more than that margin.
    const Eigen::MatrixXd g0 = gradient_at(x);
    problem.set_positions(x + v);
    const Eigen::MatrixXd Lv = problem.gradient() - g0;
    EXPECT_GT((Hv - Lv).norm(), 1e-3 * Hv.norm()) << s.name;
  }
}

// The plain and Anderson loops read only |g| (Problem::assemble_rhs_gradient_norm): the same right-hand side
// and plain step, bit for bit, as assemble_rhs, and |g| within rounding of the stored gradient's norm (a sum
// of 3 #free squares in another order: a few ulps of it, 1e-13 a wide margin), the same bits at one and
// two threads; g itself is then left unstored.
TEST_F(AcceleratedSolve, GradientNormAloneMatchesTheStoredGradient) {
  for (const Scene& s : small_scenes()) {
    ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
    Eigen::MatrixXd U = s.mesh.V;
    arap_solve(data, s.targets, U, accelerated(ArapAccelerator::None, 3)); // a deformed state
    detail::LocalGlobalProblem problem(data, s.targets, U);
    problem.local_step();
    problem.assemble_rhs();
    const double stored = problem.gradient().norm();
    const Eigen::MatrixXd step = problem.plain_step();
    double norm[2] = {0, 0};
    for (const int threads : {1, 2}) {
      set_thread_count(threads);
      norm[threads - 1] = problem.assemble_rhs_gradient_norm();
    }
    set_thread_count(0);
    EXPECT_GT(stored, 0) << s.name;
    EXPECT_LE(std::abs(norm[0] - stored), 1e-13 * stored) << s.name;
    EXPECT_EQ(norm[0], norm[1]) << s.name;
    EXPECT_EQ(problem.gradient().size(), 0) << s.name;
    EXPECT_EQ(problem.plain_step(), step) << s.name;
  }
}

// Truncated Newton reaches the rigidly moved bunny of the test above to 1e-7 of the diagonal within the 30
// iterations the issue asks for. Measured distances after 10 / 15 / 20 / 30 iterations (window 8: up to 8 CG
// steps per iteration, one solve each; trust region): spokes-rims 9.2e-6 / 1.7e-10 / 1.4e-14 / 1.2e-14, iARAP
// 3.6e-4 / 1.1e-8 / 1.0e-12 / 1.7e-14, against L-BFGS's 1.1e-4 / 2.4e-4 and Anderson's 2.4e-5 / 9.7e-5
// after 30. (Original ARAP is left out: with negative weights its energy goes below zero, so the rigid
// motion, E = 0, is a stationary point but not its minimizer; every accelerator ends 3.6e-2 of the diagonal
// away from it.)
TEST_F(AcceleratedSolve, NewtonReachesARigidMotionWithinThirtyIterations) {
  for (ArapMethod method : {ArapMethod::SpokesRims, ArapMethod::Iarap})
    EXPECT_LT(rigid_motion_distance(method, ArapAccelerator::Newton, 30), 1e-7) << arap_method_name(method);
}

// Warm start: from a converged solution the gradient rule holds within one iteration and U stays put
// (to the 1e-9 gradient level, far below 1e-7 of the diagonal).
TEST_F(AcceleratedSolve, WarmStartFromTheSolutionStopsAtOnce) {
  const Scene s = small_scenes()[3];
  ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
  const double diag = test::bbox_diagonal(s.mesh.V);
  for (ArapAccelerator a : kAccelerators) {
    ArapSolveOptions options = accelerated(a, 2000);
    options.gradient_tolerance = 1e-9;
    Eigen::MatrixXd U = s.mesh.V;
    const ArapReport cold = arap_solve(data, s.targets, U, options);
    ASSERT_TRUE(cold.converged);
    const Eigen::MatrixXd solution = U;
    options.gradient_tolerance = 1e-3; // relative to the (tiny) gradient of the warm start itself
    options.tolerance = 1e-10;
    const ArapReport warm = arap_solve(data, s.targets, U, options);
    EXPECT_LE(warm.iterations, 2) << arap_accelerator_name(a);
    EXPECT_LT(max_row_distance(U, solution), 1e-7 * diag);
    // The same U, its rotations fitted twice: warm-started Newton steps in the cold run's last local step,
    // a cold polar decomposition here; both are exact to rounding, so the energies agree to ~1e-15
    // relative per cell, summed over the cells (1e-12 leaves a wide margin at these sizes).
    EXPECT_LE(warm.initial_energy, cold.energies.back() + 1e-12 * std::abs(cold.energies.back()));
  }
}

TEST_F(AcceleratedSolve, CallbackStopsTheSolve) {
  const Scene s = small_scenes()[2];
  ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
  Eigen::MatrixXd U = s.mesh.V;
  ArapSolveOptions options = accelerated(ArapAccelerator::Lbfgs, 100);
  int calls = 0;
  options.on_iteration = [&](const ArapReport& report) {
    ++calls;
    EXPECT_EQ(report.iterations, calls);
    return report.iterations < 3;
  };
  const ArapReport report = arap_solve(data, s.targets, U, options);
  EXPECT_EQ(report.iterations, 3);
  EXPECT_FALSE(report.converged);
}

TEST_F(AcceleratedSolve, BadOptionsAreNamed) {
  const Scene s = small_scenes()[2];
  ArapData data = arap_precompute(s.mesh.V, s.mesh.F, s.fixed, s.options);
  Eigen::MatrixXd U = s.mesh.V;
  const auto expect_input_error = [&](ArapSolveOptions options, const std::string& words) {
    try {
      arap_solve(data, s.targets, U, options);
      ADD_FAILURE() << "expected InputError mentioning " << words;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  ArapSolveOptions options;
  options.window = -1;
  expect_input_error(options, "window");
  options = {};
  options.gradient_tolerance = -1e-3;
  expect_input_error(options, "gradient_tolerance");
  options.gradient_tolerance = std::nan("");
  expect_input_error(options, "gradient_tolerance");
}

} // namespace
