// The streamed local step (fit_rotations over cell_entry, polar_rotation_near from the previous rotations)
// and the regrouped right-hand side (arap_rhs over rhs_term) against the plain formulas of the paper,
// written out here: per element s_e = U^T b_e, per cell S_c = sum w_e s_e s_hat_e^T and R_c =
// polar_rotation(S_c) cold, E_c from the residuals, per element q_e = w_e (sum_c R_c) s_hat_e and
// rhs = sum_e b_e q_e^T.
#include "iarap/solver/arap.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "iarap/solver/polar_rotation.h"
#include "solver_fixtures.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

namespace {

using namespace iarap;

// The local step as the paper states it, one element and one cell at a time.
double reference_local_step(const ArapElements& el, const Eigen::MatrixXd& U, std::vector<Eigen::Matrix3d>& R,
                            Eigen::VectorXd& cell_energy) {
  Eigen::MatrixXd s(el.size(), 3);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    s.row(e).setZero();
    for (int k = 0; k < 3; ++k) s.row(e) += el.b_value(e, k) * U.row(el.b_index(e, k));
  }
  std::vector<Eigen::Matrix3d> S(static_cast<size_t>(el.num_cells), Eigen::Matrix3d::Zero());
  for (Eigen::Index e = 0; e < el.size(); ++e)
    for (int j = el.cell_start[e]; j < el.cell_start[e + 1]; ++j)
      S[static_cast<size_t>(el.cell[j])] += el.w(e) * s.row(e).transpose() * el.s_hat.row(e);
  R.resize(S.size());
  for (size_t c = 0; c < S.size(); ++c) R[c] = polar_rotation(S[c]);
  cell_energy = Eigen::VectorXd::Zero(el.num_cells);
  for (Eigen::Index e = 0; e < el.size(); ++e)
    for (int j = el.cell_start[e]; j < el.cell_start[e + 1]; ++j) {
      const int c = el.cell[j];
      cell_energy(c) +=
          0.5 * el.w(e) *
          (s.row(e).transpose() - R[static_cast<size_t>(c)] * el.s_hat.row(e).transpose()).squaredNorm();
    }
  return cell_energy.sum();
}

Eigen::MatrixXd reference_rhs(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R) {
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(el.num_vertices, 3);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    Eigen::Matrix3d Rsum = Eigen::Matrix3d::Zero();
    for (int j = el.cell_start[e]; j < el.cell_start[e + 1]; ++j) Rsum += R[static_cast<size_t>(el.cell[j])];
    const Eigen::RowVector3d q = el.w(e) * (Rsum * el.s_hat.row(e).transpose()).transpose();
    for (int k = 0; k < 3; ++k) rhs.row(el.b_index(e, k)) += el.b_value(e, k) * q;
  }
  return rhs;
}

// arap_solve's iteration with the reference steps and the factor's allocating solve.
std::vector<double> reference_solve(const ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                                    int iterations) {
  Eigen::MatrixXd U_c(data.fixed.size(), 3);
  U_c = targets;
  for (Eigen::Index k = 0; k < data.fixed.size(); ++k) U.row(data.fixed(k)) = targets.row(k);
  const Eigen::MatrixXd Lfc_Uc = data.L_fc * U_c;
  std::vector<Eigen::Matrix3d> R;
  Eigen::VectorXd cell_energy;
  std::vector<double> energies;
  reference_local_step(data.elements, U, R, cell_energy);
  for (int k = 0; k < iterations; ++k) {
    const Eigen::MatrixXd rhs = reference_rhs(data.elements, R);
    Eigen::MatrixXd B(data.free.size(), 3);
    for (Eigen::Index i = 0; i < data.free.size(); ++i) B.row(i) = rhs.row(data.free(i)) - Lfc_Uc.row(i);
    const Eigen::MatrixXd X = data.solver.solve(B);
    for (Eigen::Index i = 0; i < data.free.size(); ++i) U.row(data.free(i)) = X.row(i);
    energies.push_back(reference_local_step(data.elements, U, R, cell_energy));
  }
  return energies;
}

// The bunny bent as in the paper's experiments: bottom 10% fixed, top 10% turned by 0.5 rad and moved.
struct BentBunny {
  test::SolverMesh mesh = test::bunny();
  Eigen::VectorXi fixed;
  Eigen::MatrixXd targets;
  BentBunny() {
    const std::vector<int> bottom = test::axis_band(mesh.V, 1, 0.1, -1),
                           top = test::axis_band(mesh.V, 1, 0.1, +1);
    fixed.resize(static_cast<Eigen::Index>(bottom.size() + top.size()));
    fixed << test::to_vector(bottom), test::to_vector(top);
    targets = test::rows_of(mesh.V, fixed);
    const double diag = test::bbox_diagonal(mesh.V);
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (Eigen::Index k = static_cast<Eigen::Index>(bottom.size()); k < fixed.size(); ++k)
      targets.row(k) =
          (Q * targets.row(k).transpose()).transpose() + Eigen::RowVector3d(0.15 * diag, 0.1 * diag, 0);
  }
};

// The scene's data for `method` after `iterations` iterations of arap_solve from rest (U: the result).
ArapData solved(const BentBunny& scene, ArapMethod method, int iterations, Eigen::MatrixXd& U,
                ArapReport* report = nullptr) {
  ArapOptions options;
  options.method = method;
  options.keep_elements = true; // the reference steps read the element arrays
  ArapData data = arap_precompute(scene.mesh.V, scene.mesh.F, scene.fixed, options);
  U = scene.mesh.V;
  ArapSolveOptions solve;
  solve.max_iterations = iterations;
  solve.tolerance = -1;
  solve.accelerator =
      ArapAccelerator::None; // the paper's plain iteration, which the reference loop writes out
  const ArapReport r = arap_solve(data, scene.targets, U, solve);
  if (report) *report = r;
  return data;
}

// One step from a deformed state: the same rotations, energies and right-hand side as the plain formulas.
// Rotations to 1e-12 (polar_rotation_near and polar_rotation meet at rounding, ~1e-15, slack for
// ill-conditioned cells); energies and rhs to 1e-12 relative (rounding of sums regrouped per cell or vertex;
// original ARAP's energy is negative on the bunny, whose negative weights make it indefinite, hence |E|).
TEST(FitRotations, StreamedStepsMatchThePlainFormulas) {
  const BentBunny scene;
  const double diag = test::bbox_diagonal(scene.mesh.V);
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    Eigen::MatrixXd U;
    const ArapData data = solved(scene, method, 3, U); // a deformed state, and data.R from the step before it
    std::vector<Eigen::Matrix3d> R_ref, R_warm = data.R, R_cold;
    Eigen::VectorXd energy_ref, energy_warm, energy_cold;
    ArapElements::ValueRows workspace;
    const double E_ref = reference_local_step(data.elements, U, R_ref, energy_ref);
    const double E_warm = fit_rotations(data.elements, U, workspace, R_warm, energy_warm);
    const double E_cold = fit_rotations(data.elements, U, workspace, R_cold, energy_cold);
    double worst = 0.0;
    for (size_t c = 0; c < R_ref.size(); ++c)
      worst = std::max({worst, (R_warm[c] - R_ref[c]).norm(), (R_cold[c] - R_ref[c]).norm()});
    EXPECT_LT(worst, 1e-12) << arap_method_name(method);
    EXPECT_NEAR(E_warm, E_ref, 1e-12 * std::abs(E_ref)) << arap_method_name(method);
    EXPECT_NEAR(E_cold, E_ref, 1e-12 * std::abs(E_ref)) << arap_method_name(method);
    EXPECT_LT((energy_warm - energy_ref).cwiseAbs().maxCoeff(), 1e-12 * std::abs(E_ref))
        << arap_method_name(method);
    Eigen::MatrixXd rhs;
    arap_rhs(data.elements, R_ref, rhs);
    const Eigen::MatrixXd rhs_ref = reference_rhs(data.elements, R_ref);
    EXPECT_LT((rhs - rhs_ref).norm(), 1e-12 * rhs_ref.norm()) << arap_method_name(method);
    EXPECT_GT(std::abs(E_ref), 1e-6 * diag * diag); // the state is deformed
  }
}

// 50 iterations of arap_solve against 50 of the plain iteration: positions within 1e-10 of the bounding-box
// diagonal. Each step differs from the reference by rounding (~1e-15 relative, see above); the iteration
// is a contraction near its fixed point, so these differences do not grow beyond a few orders of
// magnitude (the distances are recorded as test properties).
TEST(FitRotations, FiftyIterationsMatchThePlainIteration) {
  const BentBunny scene;
  const double diag = test::bbox_diagonal(scene.mesh.V);
  for (ArapMethod method : {ArapMethod::Arap, ArapMethod::SpokesRims, ArapMethod::Iarap}) {
    Eigen::MatrixXd U, U_ref = scene.mesh.V;
    ArapReport report;
    const ArapData data = solved(scene, method, 50, U, &report);
    const std::vector<double> energies = reference_solve(data, scene.targets, U_ref, 50);
    const double distance = (U - U_ref).rowwise().norm().maxCoeff() / diag;
    EXPECT_LT(distance, 1e-10) << arap_method_name(method);
    EXPECT_GT((U - scene.mesh.V).rowwise().norm().maxCoeff(), 1e-2 * diag); // it did deform
    EXPECT_NEAR(report.energies.back(), energies.back(), 1e-10 * std::abs(energies.back()))
        << arap_method_name(method);
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", distance);
    RecordProperty(arap_method_name(method) + "_distance", text);
  }
}

} // namespace
