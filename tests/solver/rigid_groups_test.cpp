// Rigid parts (issue 45, item 4): ArapOptions::rigid_groups keeps each group's vertices one rigid body.
#include "iarap/core/errors.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_tets.h"
#include "problem_probe.h"
#include "solver/rigid_group_problem.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace iarap;
using test::SolverMesh;

class RigidGroups : public test::SingleThreadTest {};

// max over the members of |x_i - (R p_i + t)| for the least-squares rigid fit (R, t) of the members' rest
// positions p onto x (Kabsch by SVD, computed here independently of the library).
double rigid_misfit(const Eigen::MatrixXd& P_all, const Eigen::MatrixXd& X_all,
                    const std::vector<int>& members) {
  const Eigen::MatrixXd P = test::rows_of(P_all, test::to_vector(members));
  const Eigen::MatrixXd X = test::rows_of(X_all, test::to_vector(members));
  const Eigen::RowVector3d p0 = P.colwise().mean(), x0 = X.colwise().mean();
  const Eigen::Matrix3d S = (X.rowwise() - x0).transpose() * (P.rowwise() - p0);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  const Eigen::Matrix3d R = svd.matrixU() * D * svd.matrixV().transpose();
  double worst = 0.0;
  for (Eigen::Index k = 0; k < P.rows(); ++k)
    worst = std::max(worst, (X.row(k) - x0 - (R * (P.row(k) - p0).transpose()).transpose()).norm());
  return worst;
}

// Vertices whose coordinate `axis` lies in [lo, hi] as fractions of the bounding box.
std::vector<int> slab(const Eigen::MatrixXd& V, int axis, double lo, double hi) {
  const double a = V.col(axis).minCoeff(), b = V.col(axis).maxCoeff();
  std::vector<int> out;
  for (int v = 0; v < V.rows(); ++v) {
    const double t = (V(v, axis) - a) / (b - a);
    if (t >= lo && t <= hi) out.push_back(v);
  }
  return out;
}

struct BandedScene {
  SolverMesh m;
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
};

// The mesh with its bottom 10% along `axis` at rest and its top 10% moved by `shift` diagonals along
// `direction` and turned by `turn` radians about that axis.
BandedScene banded(SolverMesh m, int axis, const Eigen::Vector3d& direction, double shift, double turn) {
  BandedScene s;
  s.m = std::move(m);
  const Eigen::VectorXi bottom = test::to_vector(test::axis_band(s.m.V, axis, 0.1, -1));
  const Eigen::VectorXi top = test::to_vector(test::axis_band(s.m.V, axis, 0.1, +1));
  s.fixed.resize(bottom.size() + top.size());
  s.fixed << bottom, top;
  s.targets = test::rows_of(s.m.V, s.fixed);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(turn, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
  const double diagonal = test::bbox_diagonal(s.m.V);
  for (Eigen::Index k = bottom.size(); k < s.fixed.size(); ++k)
    s.targets.row(k) = (R * s.targets.row(k).transpose() + shift * diagonal * direction).transpose();
  return s;
}

ArapOptions with_groups(ArapMethod method, std::vector<std::vector<int>> groups) {
  ArapOptions options;
  options.method = method;
  options.rigid_groups = std::move(groups);
  return options;
}

ArapSolveOptions plain(int iterations) {
  ArapSolveOptions solve;
  solve.accelerator = ArapAccelerator::None;
  solve.max_iterations = iterations;
  solve.tolerance = -1; // exactly `iterations`
  return solve;
}

// The energy after each iteration is at most the one before: every block step (group rotations, cell
// rotations, global step) minimizes exactly over its block. Rounding of a sum of O(#cells) terms: 1e-12
// relative.
void expect_monotone(const ArapReport& report) {
  double previous = report.initial_energy;
  for (size_t k = 0; k < report.energies.size(); ++k) {
    EXPECT_LE(report.energies[k], previous + 1e-12 * std::abs(previous)) << "iteration " << k;
    previous = report.energies[k];
  }
}

// The criterion: a group in the middle of the bunny, bent by its top band, moves rigidly to 1e-9 of
// the diagonal (it is rigid by construction: the misfit is rounding, ~1e-16 relative), while the mesh
// around it bends; the energy falls monotonically.
TEST_F(RigidGroups, BunnyMiddleGroupMovesRigidly) {
  BandedScene s = banded(test::bunny(), 1, Eigen::Vector3d::UnitX(), 0.15, 0.5);
  const std::vector<int> middle = slab(s.m.V, 1, 0.4, 0.6);
  ASSERT_GT(middle.size(), 100u);
  ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {middle}));
  Eigen::MatrixXd U = s.m.V;
  const ArapReport report = arap_solve(data, s.targets, U, plain(30));
  const double diagonal = test::bbox_diagonal(s.m.V);
  EXPECT_LE(rigid_misfit(s.m.V, U, middle), 1e-9 * diagonal);
  // The group did move: it is not at rest, and the bend passed through it.
  EXPECT_GT((test::rows_of(U, test::to_vector(middle)) - test::rows_of(s.m.V, test::to_vector(middle)))
                .rowwise()
                .norm()
                .maxCoeff(),
            0.01 * diagonal);
  expect_monotone(report);
  EXPECT_LT(report.energies.back(), 0.9 * report.energies.front());
}

// Every method, two groups that touch (their elements share cells: the Gauss-Seidel pass over the groups
// must see the one before) and a group turning about its one fixed vertex (Pivot).
TEST_F(RigidGroups, EveryMethodTouchingGroupsAndAPivotStayRigidAndMonotone) {
  BandedScene s = banded(test::bumpy_patch(12), 0, Eigen::Vector3d::UnitZ(), 0.2, 0.4);
  const std::vector<int> left = slab(s.m.V, 0, 0.3, 0.45), right = slab(s.m.V, 0, 0.46, 0.6);
  // The pivot group: a vertex of the fixed bottom band and a strip beside the band.
  std::vector<int> pivot = slab(s.m.V, 0, 0.12, 0.25);
  pivot.push_back(s.fixed(0));
  const double diagonal = test::bbox_diagonal(s.m.V);
  for (const ArapMethod method : test::kAllMethods) {
    SCOPED_TRACE(arap_method_name(method));
    ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(method, {left, right, pivot}));
    EXPECT_EQ(data.rigid.kind[0], RigidGroupKind::Free);
    EXPECT_EQ(data.rigid.kind[2], RigidGroupKind::Pivot);
    Eigen::MatrixXd U = s.m.V;
    const ArapReport report = arap_solve(data, s.targets, U, plain(40));
    for (const auto& group : {left, right, pivot}) EXPECT_LE(rigid_misfit(s.m.V, U, group), 1e-12 * diagonal);
    // The pivot stays on its target.
    EXPECT_LE((U.row(s.fixed(0)) - s.targets.row(0)).norm(), 1e-12 * diagonal);
    expect_monotone(report);
  }
}

// Targets at rest: the rest shape is the minimum (E = 0) and the solve stays there.
TEST_F(RigidGroups, AtRestStaysAtRest) {
  BandedScene s = banded(test::bunny(), 1, Eigen::Vector3d::UnitX(), 0.0, 0.0);
  ArapData data =
      arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {slab(s.m.V, 1, 0.4, 0.6)}));
  for (const ArapAccelerator accelerator :
       {ArapAccelerator::None, ArapAccelerator::Newton, ArapAccelerator::Lbfgs, ArapAccelerator::Anderson}) {
    SCOPED_TRACE(arap_accelerator_name(accelerator));
    ArapSolveOptions solve = plain(5);
    solve.accelerator = accelerator;
    Eigen::MatrixXd U = s.m.V;
    const ArapReport report = arap_solve(data, s.targets, U, solve);
    EXPECT_LE((U - s.m.V).rowwise().norm().maxCoeff(), 1e-12 * test::bbox_diagonal(s.m.V));
    EXPECT_LE(report.energies.empty() ? report.initial_energy : report.energies.back(), 1e-20);
  }
}

// One group of every vertex held by three fixed vertices whose targets are a rigid motion: the mesh takes
// exactly that motion (energy 0); with a single fixed vertex (a pivot) the result is rigid and of energy 0
// from any guess.
TEST_F(RigidGroups, OneGroupOfEverythingIsARigidMotion) {
  const SolverMesh m = test::bumpy_patch(8);
  std::vector<int> everything(static_cast<size_t>(m.V.rows()));
  for (int v = 0; v < m.V.rows(); ++v) everything[static_cast<size_t>(v)] = v;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::RowVector3d t(0.3, -0.2, 0.5);
  const auto moved = [&](const Eigen::MatrixXd& X) -> Eigen::MatrixXd {
    return ((X * R.transpose()).rowwise() + t).eval();
  };
  const double diagonal = test::bbox_diagonal(m.V);
  const Eigen::VectorXi held = (Eigen::VectorXi(3) << 0, 8, 80).finished();
  ArapData data = arap_precompute(m.V, m.F, held, with_groups(ArapMethod::Iarap, {everything}));
  EXPECT_EQ(data.rigid.kind[0], RigidGroupKind::Held);
  Eigen::MatrixXd U = m.V;
  ArapReport report = arap_solve(data, moved(test::rows_of(m.V, held)), U, plain(3));
  EXPECT_LE((U - moved(m.V)).rowwise().norm().maxCoeff(), 1e-12 * diagonal);
  EXPECT_LE(report.energies.back(), 1e-20);

  const Eigen::VectorXi pivot = (Eigen::VectorXi(1) << 40).finished();
  ArapData turning = arap_precompute(m.V, m.F, pivot, with_groups(ArapMethod::Iarap, {everything}));
  Eigen::MatrixXd guess = moved(m.V);
  report = arap_solve(turning, test::rows_of(m.V, pivot), guess, plain(3));
  EXPECT_LE(rigid_misfit(m.V, guess, everything), 1e-12 * diagonal);
  EXPECT_LE((guess.row(40) - m.V.row(40)).norm(), 1e-12 * diagonal);
  EXPECT_LE(report.energies.back(), 1e-20);
}

// A Held group follows its fixed members' rigid motion exactly; targets off a rigid motion, and fixed
// members that cannot determine the rotation, are refused naming the group.
TEST_F(RigidGroups, HeldGroupFollowsItsTargetsAndContradictionsAreRefused) {
  BandedScene s = banded(test::bumpy_patch(10), 0, Eigen::Vector3d::UnitZ(), 0.1, 0.0);
  const std::vector<int> group = slab(s.m.V, 0, 0.85, 1.0); // holds the whole top band
  ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {group}));
  EXPECT_EQ(data.rigid.kind[0], RigidGroupKind::Held);
  Eigen::MatrixXd U = s.m.V;
  arap_solve(data, s.targets, U, plain(10)); // the top band moved as a translation: a rigid motion
  const double diagonal = test::bbox_diagonal(s.m.V);
  const Eigen::RowVector3d shift(0, 0, 0.1 * diagonal);
  for (const int i : group) EXPECT_LE((U.row(i) - s.m.V.row(i) - shift).norm(), 1e-12 * diagonal);

  Eigen::MatrixXd stretched = s.targets;
  for (Eigen::Index k = 0; k < s.fixed.size(); ++k) // the held members stretched by 1% along y: not rigid
    if (std::find(group.begin(), group.end(), s.fixed(k)) != group.end()) stretched(k, 1) *= 1.01;
  U = s.m.V;
  try {
    arap_solve(data, stretched, U, plain(1));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rigid group 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a rigid motion"), std::string::npos) << e.what();
  }
  // Two fixed members: a turn about their line is left free.
  const Eigen::VectorXi two = (Eigen::VectorXi(2) << group[0], group[1]).finished();
  EXPECT_THROW(arap_precompute(s.m.V, s.m.F, two, with_groups(ArapMethod::Iarap, {group})), InputError);
}

TEST_F(RigidGroups, BadGroupsAreRefusedNamingTheGroup) {
  const SolverMesh m = test::bumpy_patch(4);
  const Eigen::VectorXi fixed = (Eigen::VectorXi(1) << 0).finished();
  const auto message = [&](std::vector<std::vector<int>> groups) {
    try {
      arap_precompute(m.V, m.F, fixed, with_groups(ArapMethod::Iarap, std::move(groups)));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{1, 2}, {3, 99}}).find("rigid group 1 names vertex 99, out of range"),
            std::string::npos);
  EXPECT_NE(message({{1, 2}, {3}}).find("rigid group 1 has 1 vertices"), std::string::npos);
  EXPECT_NE(message({{1, 2}, {3, 2}}).find("vertex 2, already in rigid group 0"), std::string::npos);
  EXPECT_NE(message({{1, 2, 1}}).find("names vertex 1 twice"), std::string::npos);
  EXPECT_NE(message({{1, -1}}).find("out of range"), std::string::npos);
}

// An n x n bumpy patch bent by its x bands (0.2 diagonals up, turned 0.4 rad) with a Free group across the
// middle and a Pivot group: a strip beside the fixed band and one vertex of that band.
struct PivotScene {
  BandedScene scene;
  std::vector<int> middle, pivot;
};

PivotScene pivot_scene(int n) {
  PivotScene p{banded(test::bumpy_patch(n), 0, Eigen::Vector3d::UnitZ(), 0.2, 0.4), {}, {}};
  p.middle = slab(p.scene.m.V, 0, 0.4, 0.6);
  p.pivot = slab(p.scene.m.V, 0, 0.12, 0.25);
  p.pivot.push_back(p.scene.fixed(0));
  return p;
}

// The reduced problem (rigid_group_problem.h): its gradient is the derivative of E(x) = min_R energy over x
// = [y; w] and its Hessian product the derivative of that gradient, at a point where the rotation vectors
// are away from 0 (so that J(w) and the coordinates' curvature matter). Central differences along a random
// direction (its rotation rows in radians, scaled to the positions' steps by the diagonal): errors O(h^2) +
// O(eps E / h), ~1e-9 relative at h = 1e-5 of the diagonal; 1e-6 (gradient) and 1e-5 (Hessian) reject a
// missing or doubled term (order-1 errors), as the other problems' tests do.
TEST_F(RigidGroups, GradientAndHessianProductAreDerivatives) {
  const PivotScene p = pivot_scene(8);
  const BandedScene& s = p.scene;
  const double diagonal = test::bbox_diagonal(s.m.V);
  for (const ArapMethod method : test::kAllMethods) {
    SCOPED_TRACE(arap_method_name(method));
    ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(method, {p.middle, p.pivot}));
    Eigen::MatrixXd U = s.m.V;
    arap_solve(data, s.targets, U, plain(5)); // a deformed, unconverged state
    detail::RigidGroupProblem problem(data, s.targets, U, Eigen::MatrixXd(0, 3), Eigen::MatrixXd(0, 3));
    ASSERT_EQ(problem.free_count(), data.rigid.P.cols() + 2); // one rotation row per Free or Pivot group
    Eigen::MatrixXd x = problem.positions();
    x.bottomRows(2) << 0.3, -0.2, 0.4, -0.1, 0.25, 0.2; // turned off the fits by ~0.5 rad
    const auto energy_at = [&](const Eigen::MatrixXd& y) { return test::energy_at(problem, y); };
    const auto gradient_at = [&](const Eigen::MatrixXd& y) { return test::gradient_at(problem, y); };
    const Eigen::MatrixXd g = gradient_at(x);
    problem.prepare_hessian();
    std::srand(5);
    Eigen::MatrixXd v = Eigen::MatrixXd::Random(x.rows(), 3);
    v.bottomRows(2) /= diagonal;
    const Eigen::MatrixXd Hv = problem.hessian_product(v);
    const double h = 1e-5 * diagonal;
    const double slope = (energy_at(x + h * v) - energy_at(x - h * v)) / (2 * h);
    const double gv = (g.array() * v.array()).sum();
    EXPECT_NEAR(slope, gv, 1e-6 * std::abs(gv));
    const Eigen::MatrixXd fd = (gradient_at(x + h * v) - gradient_at(x - h * v)) / (2 * h);
    EXPECT_LT((Hv - fd).norm(), 1e-5 * Hv.norm());
    // The rotation rows alone (the turns' own curvature, J and dJ^T tau / dw).
    EXPECT_LT((Hv - fd).bottomRows(2).norm(), 1e-5 * Hv.bottomRows(2).norm());
  }
}

// The scene solved from its rest shape with `accelerator` to a relative energy decrease `tolerance`.
ArapReport solve_with(ArapData& data, const BandedScene& s, ArapAccelerator accelerator, double tolerance,
                      int iterations, Eigen::MatrixXd& U) {
  U = s.m.V;
  ArapSolveOptions o;
  o.accelerator = accelerator;
  o.tolerance = tolerance;
  o.max_iterations = iterations;
  return arap_solve(data, s.targets, U, o);
}

// Iterations until the energy is within 1e-6 of the minimum E* (`iarap bench --converge`'s gap).
int iterations_to_gap(const ArapReport& r, double E_star) {
  for (size_t k = 0; k < r.energies.size(); ++k)
    if (r.energies[k] - E_star <= 1e-6 * E_star) return static_cast<int>(k) + 1;
  return std::numeric_limits<int>::max();
}

// Every accelerator minimizes the same E(x) as the plain iteration and reaches the same minimum: each runs
// to a relative energy decrease of 1e-13; the results agree to 1e-6 of the diagonal (the energy is flat to
// second order at the minimum: positions settle to ~sqrt of the stopping rule's precision) and the energies
// to 1e-9; every accepted step lowers the energy; the groups stay rigid to 1e-9 of the diagonal (rounding,
// ~1e-15: U is placed from R_g and t_g) and the pivot on its target.
TEST_F(RigidGroups, EveryAcceleratorReachesThePlainMinimum) {
  const PivotScene p = pivot_scene(10);
  const BandedScene& s = p.scene;
  const std::vector<int>&middle = p.middle, &pivot = p.pivot;
  const double diagonal = test::bbox_diagonal(s.m.V);
  for (const ArapMethod method : test::kAllMethods) {
    SCOPED_TRACE(arap_method_name(method));
    ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(method, {middle, pivot}));
    Eigen::MatrixXd U_plain;
    const ArapReport plain_report = solve_with(data, s, ArapAccelerator::None, 1e-13, 20000, U_plain);
    ASSERT_TRUE(plain_report.converged);
    const double E = plain_report.energies.back();
    for (const ArapAccelerator accelerator :
         {ArapAccelerator::Newton, ArapAccelerator::Lbfgs, ArapAccelerator::Anderson}) {
      SCOPED_TRACE(arap_accelerator_name(accelerator));
      Eigen::MatrixXd U;
      const ArapReport report = solve_with(data, s, accelerator, 1e-13, 2000, U);
      ASSERT_TRUE(report.converged);
      EXPECT_LT((U - U_plain).rowwise().norm().maxCoeff(), 1e-6 * diagonal);
      EXPECT_NEAR(report.energies.back(), E, 1e-9 * E);
      expect_monotone(report);
      for (const auto& group : {middle, pivot}) EXPECT_LE(rigid_misfit(s.m.V, U, group), 1e-9 * diagonal);
      EXPECT_LE((U.row(s.fixed(0)) - s.targets.row(0)).norm(), 1e-12 * diagonal);
      std::cout << arap_method_name(method) << " " << arap_accelerator_name(accelerator)
                << ": iterations to 1e-6 of the minimum " << iterations_to_gap(report, E) << " (plain "
                << iterations_to_gap(plain_report, E) << ")\n";
    }
  }
  // The default options (Newton) solve too, as a user passing groups alone gets.
  ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {middle, pivot}));
  Eigen::MatrixXd U = s.m.V;
  const ArapReport report = arap_solve(data, s.targets, U, ArapSolveOptions());
  EXPECT_EQ(report.accelerator, ArapSolveOptions().accelerator);
  EXPECT_LE(rigid_misfit(s.m.V, U, middle), 1e-9 * diagonal);
  expect_monotone(report);
}

// The measurement the issue asks for: the bunny bent by its top band with two rigid groups (a slab in the
// middle and one near the top), iARAP, Newton against plain iterations to within 1e-6 of the minimum (E*
// the lower of the two runs to a relative decrease of 1e-12, or 2000 iterations). Newton needs at least 5x
// fewer (measured: plain 1682, Newton 16; Newton stops at the 1e-12 decrease after 23, plain is 1.4e-7
// above E* after 2000); both keep the groups rigid to 1e-9 of the diagonal.
TEST_F(RigidGroups, NewtonIsFiveTimesFewerIterationsThanPlainOnTheBunny) {
  BandedScene s = banded(test::bunny(), 1, Eigen::Vector3d::UnitX(), 0.15, 0.5);
  const std::vector<int> middle = slab(s.m.V, 1, 0.4, 0.55), upper = slab(s.m.V, 1, 0.7, 0.8);
  ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {middle, upper}));
  Eigen::MatrixXd U_plain, U_newton;
  const ArapReport plain_report = solve_with(data, s, ArapAccelerator::None, 1e-12, 2000, U_plain);
  ASSERT_EQ(plain_report.energies.size(), 2000u);
  const ArapReport newton_report = solve_with(data, s, ArapAccelerator::Newton, 1e-12, 200, U_newton);
  ASSERT_TRUE(newton_report.converged);
  const double E_star = std::min(plain_report.energies.back(), newton_report.energies.back());
  // Plain is still ~1e-7 above the minimum after its 2000 iterations (the reason for Newton): not below it.
  EXPECT_GE(plain_report.energies.back(), newton_report.energies.back() - 1e-12 * E_star);
  const double diagonal = test::bbox_diagonal(s.m.V);
  for (const auto& group : {middle, upper}) {
    EXPECT_LE(rigid_misfit(s.m.V, U_plain, group), 1e-9 * diagonal);
    EXPECT_LE(rigid_misfit(s.m.V, U_newton, group), 1e-9 * diagonal);
  }
  const int plain_iterations = iterations_to_gap(plain_report, E_star);
  const int newton_iterations = iterations_to_gap(newton_report, E_star);
  EXPECT_LE(5 * newton_iterations, plain_iterations);
  std::cout << "bunny, two rigid groups (" << middle.size() << " and " << upper.size()
            << " vertices): iterations to 1e-6 of the minimum: plain " << plain_iterations << ", newton "
            << newton_iterations << "; to the 1e-12 decrease: plain " << plain_report.iterations
            << ", newton " << newton_report.iterations << "\n";
}

// Rotation smoothing couples the cells' rotations, the groups tie theirs: no joint local step, refused.
TEST_F(RigidGroups, RotationSmoothingIsRefused) {
  BandedScene s = banded(test::bumpy_patch(6), 0, Eigen::Vector3d::UnitZ(), 0.1, 0.0);
  ArapData data =
      arap_precompute(s.m.V, s.m.F, s.fixed, with_groups(ArapMethod::Iarap, {slab(s.m.V, 0, 0.4, 0.6)}));
  ArapSolveOptions solve;
  solve.accelerator = ArapAccelerator::None;
  solve.rotation_smoothing = 0.02;
  Eigen::MatrixXd U = s.m.V;
  try {
    arap_solve(data, s.targets, U, solve);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rotation smoothing"), std::string::npos) << e.what();
  }
}

// Soft points, forces, a new fixed set (arap_set_fixed rebuilds the groups' system), a planar mesh and a
// tetrahedral one: the groups stay rigid and the energy monotone.
TEST_F(RigidGroups, SoftPointsForcesNewFixedSetPlanarAndTets) {
  BandedScene s = banded(test::bumpy_patch(10), 0, Eigen::Vector3d::UnitZ(), 0.1, 0.0);
  const std::vector<int> group = slab(s.m.V, 0, 0.4, 0.6);
  const double diagonal = test::bbox_diagonal(s.m.V);
  ArapSoftConstraints soft;
  soft.vertices = (Eigen::VectorXi(1) << group[0]).finished();
  soft.vertex_weights = Eigen::VectorXd::Constant(1, 10.0);
  ArapData data = arap_precompute(s.m.V, s.m.F, s.fixed, soft, with_groups(ArapMethod::Iarap, {group}));
  ArapSolveOptions solve = plain(20);
  solve.forces = Eigen::MatrixXd::Zero(s.m.V.rows(), 3);
  solve.forces.col(1).setConstant(0.01);
  const Eigen::MatrixXd soft_target = s.m.V.row(group[0]) + Eigen::RowVector3d(0, 0, 0.2 * diagonal);
  Eigen::MatrixXd U = s.m.V;
  ArapReport report = arap_solve(data, s.targets, soft_target, U, solve);
  SCOPED_TRACE("soft and forces");
  EXPECT_LE(rigid_misfit(s.m.V, U, group), 1e-12 * diagonal);
  expect_monotone(report);
  EXPECT_GT(report.penalty, 0.0);
  EXPECT_LT(report.potential, 0.0);

  const Eigen::VectorXi bottom = s.fixed.head(s.fixed.size() / 2);
  arap_set_fixed(data, bottom);
  U = s.m.V;
  report = arap_solve(data, s.targets.topRows(bottom.size()), soft_target, U, plain(20));
  SCOPED_TRACE("new fixed set");
  EXPECT_LE(rigid_misfit(s.m.V, U, group), 1e-12 * diagonal);
  expect_monotone(report);

  // Planar: the patch flattened, its top band moved in the plane; z stays 0.
  SolverMesh flat = test::bumpy_patch(10);
  flat.V.col(2).setZero();
  BandedScene p = banded(flat, 0, Eigen::Vector3d::UnitY(), 0.2, 0.0);
  ArapOptions planar = with_groups(ArapMethod::Iarap, {slab(flat.V, 0, 0.4, 0.6)});
  planar.planar = true;
  ArapData flat_data = arap_precompute(flat.V, flat.F, p.fixed, planar);
  for (const ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    SCOPED_TRACE(std::string("planar ") + arap_accelerator_name(accelerator));
    ArapSolveOptions solve_planar = plain(20);
    solve_planar.accelerator = accelerator;
    U = flat.V;
    report = arap_solve(flat_data, p.targets, U, solve_planar);
    EXPECT_EQ(U.col(2).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE(rigid_misfit(flat.V, U, slab(flat.V, 0, 0.4, 0.6)), 1e-12 * diagonal);
    expect_monotone(report);
  }

  // Tets: a 3 x 3 x 3 cube of 6 tets per cell, its middle layer rigid.
  const int n = 4;
  Eigen::MatrixXd V(n * n * n, 3);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) V.row((k * n + j) * n + i) << i, j, k;
  std::vector<Eigen::Vector4i> tets;
  const int cube[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for (int k = 0; k + 1 < n; ++k)
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i)
        for (const auto& t : cube) {
          Eigen::Vector4i tet;
          for (int c = 0; c < 4; ++c)
            tet(c) = ((k + (t[c] >> 2 & 1)) * n + j + (t[c] >> 1 & 1)) * n + i + (t[c] & 1);
          tets.push_back(tet);
        }
  Eigen::MatrixXi T(static_cast<Eigen::Index>(tets.size()), 4);
  for (size_t t = 0; t < tets.size(); ++t) T.row(static_cast<Eigen::Index>(t)) = tets[t].transpose();
  BandedScene c = banded({V, Eigen::MatrixXi()}, 2, Eigen::Vector3d::UnitX(), 0.2, 0.3);
  const std::vector<int> layer = slab(V, 2, 0.3, 0.7);
  ArapData tet_data = arap_precompute_tets(V, T, c.fixed, with_groups(ArapMethod::Iarap, {layer}));
  for (const ArapAccelerator accelerator : {ArapAccelerator::None, ArapAccelerator::Newton}) {
    SCOPED_TRACE(std::string("tets ") + arap_accelerator_name(accelerator));
    ArapSolveOptions solve_tets = plain(20);
    solve_tets.accelerator = accelerator;
    U = V;
    report = arap_solve(tet_data, c.targets, U, solve_tets);
    EXPECT_LE(rigid_misfit(V, U, layer), 1e-12 * test::bbox_diagonal(V));
    expect_monotone(report);
  }
}

} // namespace
