#include "iarap/solver/arap.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "intrinsic/mesh_generators.h"
#include "solver_fixtures.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <random>

namespace {

using namespace iarap;
using test::kAllMethods;
using test::max_row_distance;
using test::SolverMesh;

ArapOptions with_method(ArapMethod method) {
  ArapOptions options;
  options.method = method;
  options.keep_elements = true; // tests below read the element arrays
  return options;
}

// The bottom and top 10% of the bounding box along y: the paper's rest-stability setting.
Eigen::VectorXi bottom_and_top(const Eigen::MatrixXd& V) {
  std::vector<int> fixed = test::axis_band(V, 1, 0.1, -1);
  const std::vector<int> top = test::axis_band(V, 1, 0.1, +1);
  fixed.insert(fixed.end(), top.begin(), top.end());
  return test::to_vector(fixed);
}

template <class F> void expect_error_mentions(F&& call, const std::string& words) {
  try {
    call();
    ADD_FAILURE() << "expected an exception mentioning '" << words << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(Arap, MethodNamesRoundTrip) {
  for (ArapMethod m : kAllMethods) EXPECT_EQ(parse_arap_method(arap_method_name(m)), m);
  expect_error_mentions([] { parse_arap_method("spokes"); }, "unknown ARAP method 'spokes'");
}

// At rest every cell covariance is sum_e w_e s_hat s_hat^T, symmetric positive semi-definite when the
// weights are positive (spokes-and-rims: per-triangle PSD sums; iARAP: positive intrinsic Delaunay
// weights), so R = I and both E and dE/dV vanish up to the rounding of L V (relative 1e-12).
TEST(Arap, RestHasZeroEnergyAndGradient) {
  const SolverMesh bunny = test::bunny();
  const SolverMesh lattice = test::lattice_patch(12);
  for (ArapMethod method : kAllMethods) {
    // Original ARAP is only rest-stable where no weight is negative: checked on the Delaunay lattice
    // here; on the bunny its non-zero rest gradient is the defect measured in RestStability below.
    const SolverMesh& m = method == ArapMethod::Arap ? lattice : bunny;
    const ArapData data = arap_precompute(m.V, m.F, Eigen::VectorXi::Constant(1, 0), with_method(method));
    if (method == ArapMethod::Arap) {
      ASSERT_GT(data.elements.w.minCoeff(), 0.0);
    }
    const double scale = (data.L.cwiseAbs() * m.V.cwiseAbs()).norm(); // size of the terms in L V
    EXPECT_LT(std::abs(arap_energy(data, m.V)), 1e-24 * scale * scale) << arap_method_name(method);
    EXPECT_LT(arap_gradient(data, m.V).norm(), 1e-12 * scale) << arap_method_name(method);
  }
}

// arap_precompute factorizes iARAP's L as twice the cotan Laplacian of the input (cotan_system_matrix)
// before the intrinsic triangulation exists. The checked path: the assembly from iARAP's own elements,
// 2 B^T D_w B, is the same matrix, on a closed mesh (bunny), on non-Delaunay patches with boundary, with and
// without boundary refinement (inserted points on the sheared strip). 1e-12 relative: the sums differ in
// grouping only. On a mesh whose degenerate faces are mollified the identity fails and L comes from the
// elements.
TEST(Arap, IarapSystemMatrixIsTheCotanLaplacian) {
  const SolverMesh bunny = test::bunny();
  const SolverMesh patch = test::bumpy_patch(14);
  const test::TestMesh sheared = test::sheared_strip(16, 4, 2.0); // obtuse boundary edges: points inserted
  const SolverMesh strip{sheared.V, sheared.F};
  for (const SolverMesh* m : {&bunny, &patch, &strip})
    for (const bool refine : {false, true}) {
      ArapOptions options = with_method(ArapMethod::Iarap);
      options.intrinsic.refine_boundary = refine;
      const ArapData data = arap_precompute(m->V, m->F, Eigen::VectorXi::Constant(1, 0), options);
      const Eigen::SparseMatrix<double> BtDwB = element_system_matrix(data.elements);
      EXPECT_LT((data.L - BtDwB).norm(), 1e-12 * BtDwB.norm()) << "refine " << refine;
      EXPECT_EQ(data.intrinsic.mollify_delta, 0.0);
      if (m == &strip && refine) {
        EXPECT_GT(data.intrinsic.inserted_points, 0) << "the sheared strip should get points";
      }
    }
  // A sliver (zero-area face) is mollified: L is then 2 B^T D_w B of the mollified lengths.
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 1;
  const ArapData sliver = arap_precompute(V, F, Eigen::Vector2i(0, 1), with_method(ArapMethod::Iarap));
  EXPECT_GT(sliver.intrinsic.mollify_delta, 0.0);
  EXPECT_LT((sliver.L - element_system_matrix(sliver.elements)).norm(), 1e-12 * sliver.L.norm());
}

TEST(Arap, OriginalArapHasNonZeroRestGradientOnBunny) {
  const SolverMesh m = test::bunny();
  const ArapData data =
      arap_precompute(m.V, m.F, Eigen::VectorXi::Constant(1, 0), with_method(ArapMethod::Arap));
  const double scale = (data.L.cwiseAbs() * m.V.cwiseAbs()).norm();
  EXPECT_GT(arap_gradient(data, m.V).norm(), 1e-6 * scale);
}

// Moving the constraints by one rigid motion must move the whole mesh by it (the energy is invariant and
// zero there). Tolerance 1e-8 of the bounding box: the iteration runs until the energy stops decreasing.
// A small non-Delaunay patch (spokes-and-rims, iARAP) and the Delaunay lattice (original ARAP, see
// RestHasZeroEnergyAndGradient) keep the ~1000 linearly converging iterations cheap; on bunny.off the
// same holds (measured: 2.8e-14 and 5.0e-14 of the diagonal after 879 and 1052 iterations).
TEST(Arap, RigidMotionOfConstraintsMovesTheMeshRigidly) {
  const SolverMesh patch = test::bumpy_patch(10);
  const SolverMesh lattice = test::lattice_patch(12);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (ArapMethod method : kAllMethods) {
    const SolverMesh& m = method == ArapMethod::Arap ? lattice : patch;
    const double diag = test::bbox_diagonal(m.V);
    const Eigen::RowVector3d t(0.1 * diag, -0.2 * diag, 0.3 * diag);
    const Eigen::MatrixXd moved = (m.V * Q.transpose()).rowwise() + t;
    const Eigen::VectorXi fixed = bottom_and_top(m.V);
    ArapData data = arap_precompute(m.V, m.F, fixed, with_method(method));
    Eigen::MatrixXd U = m.V;
    ArapSolveOptions options;
    options.max_iterations = 3000;
    options.tolerance = 0.0;
    const ArapReport report = arap_solve(data, test::rows_of(moved, fixed), U, options);
    EXPECT_TRUE(report.converged) << arap_method_name(method);
    EXPECT_LT(max_row_distance(U, moved), 1e-8 * diag)
        << arap_method_name(method) << " after " << report.iterations << " iterations";
    for (const Eigen::Matrix3d& R : arap_rotations(data)) EXPECT_LT((R - Q).norm(), 1e-6);
  }
}

// The paper's central claim: constraints at rest, start at rest, 50 iterations. Spokes-and-rims and iARAP
// stay put to rounding (1e-9 of the bounding box is ~1e5 ulps of slack for 50 solves); original ARAP's
// negative weights turn some rest covariances indefinite, the fitted rotations are not the identity and
// the mesh creases. Measured on bunny.off: original ARAP drifts by 3.3e-2 of the bounding box diagonal
// in 50 iterations (its energy goes negative, -4.5e-3), spokes-and-rims and iARAP by ~1e-14; 1e-4 is
// far above rounding yet well below what original ARAP does.
TEST(Arap, RestStabilityOnBunny) {
  const SolverMesh m = test::bunny();
  const double diag = test::bbox_diagonal(m.V);
  const Eigen::VectorXi fixed = bottom_and_top(m.V);
  ArapSolveOptions options;
  options.max_iterations = 50;
  options.tolerance = -1.0; // exactly 50 iterations
  for (ArapMethod method : kAllMethods) {
    ArapData data = arap_precompute(m.V, m.F, fixed, with_method(method));
    Eigen::MatrixXd U = m.V;
    const ArapReport report = arap_solve(data, test::rows_of(m.V, fixed), U, options);
    ASSERT_EQ(report.iterations, 50);
    const double drift = max_row_distance(U, m.V) / diag;
    RecordProperty(arap_method_name(method) + "_drift", std::to_string(drift));
    if (method == ArapMethod::Arap)
      EXPECT_GT(drift, 1e-4) << "original ARAP should crease the bunny at rest";
    else
      EXPECT_LT(drift, 1e-9) << arap_method_name(method);
  }
}

// On a Delaunay mesh the intrinsic triangulation is the mesh itself, every segment is an edge with
// sigma = 1 and iARAP is original ARAP (paper Fig. 11).
TEST(Arap, IarapEqualsArapOnDelaunayCube) {
  IARAP_SHARED_MESH_OR_SKIP(path, "cube.obj");
  const MeshData m = read_mesh(path);
  const double diag = test::bbox_diagonal(m.V);
  std::vector<int> bottom = test::axis_band(m.V, 1, 0.05, -1), top = test::axis_band(m.V, 1, 0.05, +1);
  Eigen::VectorXi fixed = test::to_vector(bottom), handle = test::to_vector(top);
  Eigen::VectorXi all(fixed.size() + handle.size());
  all << fixed, handle;
  Eigen::MatrixXd targets = test::rows_of(m.V, all);
  targets.bottomRows(handle.size()).col(2).array() += 0.2 * diag; // top pushed backwards (paper Fig. 11)
  ArapSolveOptions options;
  options.max_iterations = 20;
  options.tolerance = -1.0;
  // The plain iteration: the two systems agree to rounding, and its iterates keep them together; an
  // accelerator's discrete choices (a trust region's accept/reject, CG's stop) may amplify that rounding.
  options.accelerator = ArapAccelerator::None;
  Eigen::MatrixXd results[2];
  int k = 0;
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::Iarap}) {
    ArapData data = arap_precompute(m.V, m.F, all, with_method(method));
    results[k] = m.V;
    arap_solve(data, targets, results[k++], options);
  }
  EXPECT_GT(max_row_distance(results[0], m.V), 1e-2 * diag); // it did deform
  EXPECT_LT(max_row_distance(results[0], results[1]), 1e-10 * diag);
}

// Block descent never increases the energy when every local and global step is a true minimization
// (positive definite L and a minimizing rotation): spokes-and-rims and iARAP. 1e-12 relative: rounding.
TEST(Arap, EnergyNeverIncreases) {
  const SolverMesh m = test::bunny();
  const double diag = test::bbox_diagonal(m.V);
  const std::vector<int> bottom = test::axis_band(m.V, 1, 0.1, -1), top = test::axis_band(m.V, 1, 0.1, +1);
  Eigen::VectorXi fixed(static_cast<Eigen::Index>(bottom.size() + top.size()));
  fixed << test::to_vector(bottom), test::to_vector(top);
  Eigen::MatrixXd targets = test::rows_of(m.V, fixed);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (Eigen::Index k = static_cast<Eigen::Index>(bottom.size()); k < fixed.size(); ++k)
    targets.row(k) =
        (Q * targets.row(k).transpose()).transpose() + Eigen::RowVector3d(0.15 * diag, 0.1 * diag, 0);
  for (ArapMethod method : {ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    ArapData data = arap_precompute(m.V, m.F, fixed, with_method(method));
    Eigen::MatrixXd U = m.V;
    ArapSolveOptions options;
    options.max_iterations = 40;
    options.tolerance = -1.0;
    const ArapReport report = arap_solve(data, targets, U, options);
    double previous = report.initial_energy;
    ASSERT_GT(previous, 0.0);
    for (size_t k = 0; k < report.energies.size(); ++k) {
      EXPECT_LE(report.energies[k], previous * (1 + 1e-12))
          << arap_method_name(method) << " iteration " << k + 1;
      previous = report.energies[k];
    }
    EXPECT_LT(report.energies.back(), 0.5 * report.energies.front());
    EXPECT_NEAR(arap_energy(data, U), report.energies.back(), 1e-12 * report.energies.back());
    EXPECT_NEAR(arap_cell_energy(data, U).sum(), report.energies.back(), 1e-12 * report.energies.back());
  }
}

// Eq. 14 against central differences of E(U) = min_R energy (envelope theorem). h = 1e-5 of the size:
// truncation ~h^2 and rounding ~eps E / h both sit far below the 1e-5 relative tolerance.
TEST(Arap, GradientMatchesFiniteDifferences) {
  const SolverMesh m = test::bumpy_patch(4);
  const double diag = test::bbox_diagonal(m.V);
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 0.05 * diag);
  Eigen::MatrixXd U = m.V;
  for (Eigen::Index i = 0; i < U.size(); ++i) U(i) += noise(rng);
  const double h = 1e-5 * diag;
  for (ArapMethod method : kAllMethods) {
    const ArapData data = arap_precompute(m.V, m.F, Eigen::VectorXi::Constant(1, 0), with_method(method));
    const Eigen::MatrixXd g = arap_gradient(data, U);
    Eigen::MatrixXd fd(U.rows(), 3);
    for (Eigen::Index i = 0; i < U.size(); ++i) {
      Eigen::MatrixXd Up = U, Um = U;
      Up(i) += h;
      Um(i) -= h;
      fd(i) = (arap_energy(data, Up) - arap_energy(data, Um)) / (2 * h);
    }
    EXPECT_LT((g - fd).norm(), 1e-5 * g.norm()) << arap_method_name(method);
  }
}

TEST(Arap, BadConstraintSetsAreNamed) {
  const SolverMesh m = test::bumpy_patch(3); // 16 vertices
  const ArapOptions options = with_method(ArapMethod::SpokesRims);
  expect_error_mentions([&] { arap_precompute(m.V, m.F, Eigen::VectorXi(0), options); }, "empty");
  expect_error_mentions([&] { arap_precompute(m.V, m.F, Eigen::Vector3i(0, 16, 2), options); },
                        "fixed[1] = 16 is out of range; mesh has 16 vertices");
  expect_error_mentions([&] { arap_precompute(m.V, m.F, Eigen::Vector3i(0, 5, 5), options); },
                        "fixed[2] = 5 repeats fixed[1]");
  ArapData data = arap_precompute(m.V, m.F, Eigen::Vector2i(0, 5), options);
  Eigen::MatrixXd U = m.V;
  expect_error_mentions([&] { arap_solve(data, Eigen::MatrixXd::Zero(3, 3), U); },
                        "targets must be 2 x 3, got 3 x 3");
  Eigen::MatrixXd targets = test::rows_of(m.V, Eigen::Vector2i(0, 5));
  targets(1, 2) = std::numeric_limits<double>::quiet_NaN();
  expect_error_mentions([&] { arap_solve(data, targets, U); }, "targets row 1 is not finite");
  targets(1, 2) = 0.0;
  Eigen::MatrixXd short_guess = m.V.topRows(10);
  expect_error_mentions([&] { arap_solve(data, targets, short_guess); }, "initial guess U must be 16 x 3");
  ArapSolveOptions negative;
  negative.max_iterations = -1;
  expect_error_mentions([&] { arap_solve(data, targets, U, negative); },
                        "iterations must be an integer in [0, 1000000]; got -1");
  // A failed arap_set_fixed leaves the previous constraints in place.
  EXPECT_THROW(arap_set_fixed(data, Eigen::Vector2i(1, -3)), InputError);
  EXPECT_EQ(data.fixed, Eigen::Vector2i(0, 5));
  EXPECT_NO_THROW(arap_solve(data, targets, U));
}

// With two threads the element build runs beside CHOLMOD (original ARAP: the analysis, in a two-thread
// OpenMP region; iARAP: the factorization, the build on a std::thread): an error it throws there must come
// out of arap_precompute as the same typed exception, on one thread and on two.
TEST(Arap, ErrorsFromTheBuildBesideTheAnalysisAreRethrown) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 1; // face 1 has three collinear corners: zero area
  ArapOptions iarap_strict = with_method(ArapMethod::Iarap);
  iarap_strict.intrinsic.mollify = false;
  for (const int threads : {1, 2}) {
    set_thread_count(threads);
    try {
      arap_precompute(V, F, Eigen::Vector2i(0, 1), with_method(ArapMethod::Arap));
      ADD_FAILURE() << "expected TopologyError, " << threads << " threads";
    } catch (const TopologyError& e) {
      EXPECT_NE(std::string(e.what()).find("face 1 is degenerate"), std::string::npos) << e.what();
    }
    try {
      arap_precompute(V, F, Eigen::Vector2i(0, 1), iarap_strict);
      ADD_FAILURE() << "expected TopologyError, " << threads << " threads";
    } catch (const TopologyError& e) {
      EXPECT_NE(std::string(e.what()).find("face 1 is degenerate"), std::string::npos) << e.what();
    }
  }
  set_thread_count(0);
}

TEST(Arap, UnconstrainedComponentIsNamedOrPinned) {
  const SolverMesh m = test::two_copies(test::bumpy_patch(3)); // components 0 (0..15) and 1 (16..31)
  const Eigen::VectorXi fixed = Eigen::Vector2i(0, 3);
  for (ArapMethod method : kAllMethods)
    expect_error_mentions([&] { arap_precompute(m.V, m.F, fixed, with_method(method)); },
                          "connected component 1 (16 vertices, e.g. vertex 16) has no constrained vertex");
  ArapOptions options = with_method(ArapMethod::SpokesRims);
  options.pin_unconstrained_components = true;
  ArapData data = arap_precompute(m.V, m.F, fixed, options);
  EXPECT_EQ(data.pinned, Eigen::VectorXi::Constant(1, 16));
  Eigen::MatrixXd U = m.V;
  Eigen::MatrixXd targets = test::rows_of(m.V, fixed);
  targets.row(1) += Eigen::RowVector3d(0.0, 0.0, 0.3);
  arap_solve(data, targets, U);
  // The pinned copy has nothing pulling it: it stays where the initial guess put it.
  EXPECT_LT(max_row_distance(U.bottomRows(16), m.V.bottomRows(16)), 1e-12);
  EXPECT_GT(max_row_distance(U.topRows(16), m.V.topRows(16)), 1e-2);
}

// New targets reuse the factorization; copies solve independently; thread count changes nothing but time.
TEST(Arap, ReuseCopyAndThreadsGiveTheSameResult) {
  const SolverMesh m = test::bunny();
  const Eigen::VectorXi fixed = bottom_and_top(m.V);
  Eigen::MatrixXd targets = test::rows_of(m.V, fixed);
  targets.col(0).array() +=
      0.05 * test::bbox_diagonal(m.V) * (targets.col(1).array() - m.V.col(1).mean()).sign();
  ArapSolveOptions options;
  options.max_iterations = 10;
  options.tolerance = -1.0;
  ArapData data = arap_precompute(m.V, m.F, fixed, with_method(ArapMethod::Iarap));
  EXPECT_NE(arap_factorization(data), FactorizationKind::None);
  ArapData copy = data;
  Eigen::MatrixXd results[3] = {m.V, m.V, m.V};
  set_thread_count(1);
  arap_solve(data, targets, results[0], options);
  arap_solve(copy, targets, results[1], options);
  set_thread_count(2);
  arap_solve(data, targets, results[2], options);
  set_thread_count(0);
  const double diag = test::bbox_diagonal(m.V);
  EXPECT_GT(max_row_distance(results[0], m.V), 1e-3 * diag);
  EXPECT_LT(max_row_distance(results[0], results[1]), 1e-12 * diag);
  EXPECT_LT(max_row_distance(results[0], results[2]), 1e-12 * diag);
}

} // namespace
