#include "local_global_problem.h"

#include "visit_order.h"

#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace iarap::detail {

LocalGlobalProblem::LocalGlobalProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U)
    : data_(data), U_(U) {
  // Constrained positions in L_fc's column order: targets, then pinned vertices where the guess has them.
  Eigen::MatrixXd U_c(data.fixed.size() + data.pinned.size(), 3);
  U_c.topRows(data.fixed.size()) = targets;
  for (Eigen::Index k = 0; k < data.pinned.size(); ++k)
    U_c.row(data.fixed.size() + k) = U.row(data.pinned(k));
  for (Eigen::Index k = 0; k < data.fixed.size(); ++k)
    U.row(data.fixed(k)) = targets.row(k);
  Lfc_Uc_ = data.L_fc * U_c;
  const ArapElements& el = data.elements;
  visit_rows(el, U, U_rows_);
  std::vector<int> position(el.visit_order.size());
  for (size_t p = 0; p < position.size(); ++p) position[static_cast<size_t>(el.visit_order[p])] = static_cast<int>(p);
  free_row_.resize(data.free.size());
  for (Eigen::Index i = 0; i < data.free.size(); ++i) free_row_(i) = position[static_cast<size_t>(data.free(i))];
  R_spare_.resize(static_cast<size_t>(el.num_cells));

  // Column j of the symmetric L is its row j: copying the free columns gives the free rows, transposed.
  const Eigen::Index n = data.L.rows(), nf = data.free.size();
  Eigen::Index nnz = 0;
  for (Eigen::Index i = 0; i < nf; ++i)
    nnz += data.L.outerIndexPtr()[data.free(i) + 1] - data.L.outerIndexPtr()[data.free(i)];
  L_free_cols_.resize(n, nf);
  L_free_cols_.resizeNonZeros(nnz);
  Eigen::Index k = 0;
  L_free_cols_.outerIndexPtr()[0] = 0;
  for (Eigen::Index i = 0; i < nf; ++i) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(data.L, data.free(i)); it; ++it) {
      L_free_cols_.innerIndexPtr()[k] = position[static_cast<size_t>(it.row())];
      L_free_cols_.valuePtr()[k++] = it.value();
    }
    L_free_cols_.outerIndexPtr()[i + 1] = static_cast<int>(k);
  }
  B_.resize(nf, 3);
  X_.resize(nf, 3);
  // The first fit starts cold (fit_rotations warm-starts from rotations it is given): a solve's result then
  // depends on its inputs only, bit for bit, not on what earlier solves left in data.R.
  data.R.clear();
}

LocalGlobalProblem::~LocalGlobalProblem() {
  for (Eigen::Index i = 0; i < free_count(); ++i)
    U_.row(data_.free(i)) = U_rows_.row(free_row_(i));
  if (data_.R.size() != R_spare_.size()) return; // no local step ran
  rotations_from_visit_order(data_.elements, data_.R, R_spare_);
  data_.R.swap(R_spare_);
}

Eigen::MatrixXd LocalGlobalProblem::positions() const {
  Eigen::MatrixXd x(free_count(), 3);
  for (Eigen::Index i = 0; i < free_count(); ++i)
    x.row(i) = U_rows_.row(free_row_(i));
  return x;
}

void LocalGlobalProblem::set_positions(const Eigen::MatrixXd& x) {
  for (Eigen::Index i = 0; i < free_count(); ++i)
    U_rows_.row(free_row_(i)) = x.row(i);
}

double LocalGlobalProblem::local_step() {
  return fit_rotations_in_visit_order(data_.elements, U_rows_, data_.R, cell_energy_);
}

void LocalGlobalProblem::assemble_rhs() {
  arap_rhs_in_visit_order(data_.elements, data_.R, rhs_); // Eq. 16
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < free_count(); ++i)
    B_.row(i) = rhs_.row(free_row_(i)) - Lfc_Uc_.row(i);
}

const Eigen::MatrixXd& LocalGlobalProblem::plain_step() {
  ++solves_;
  data_.solver.solve(B_, X_); // three coordinates at once
  return X_;
}

const Eigen::MatrixXd& LocalGlobalProblem::gradient() {
  // (L U)_f - rhs_f = L_ff x + L_fc U_c - rhs_f = L_ff x - B, in one pass over the free rows of L (Eigen's
  // product made a pass per coordinate and two temporaries), parallel over rows as Eigen's was.
  const Eigen::Index nf = free_count();
  Eigen::MatrixXd& g = g_;
  g.resize(nf, 3);
  const int* outer = L_free_cols_.outerIndexPtr();
  const int* row = L_free_cols_.innerIndexPtr();
  const double* value = L_free_cols_.valuePtr();
  const double* u = U_rows_.data();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < nf; ++i) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const double* ur = u + 3 * row[k];
      a0 += value[k] * ur[0];
      a1 += value[k] * ur[1];
      a2 += value[k] * ur[2];
    }
    g(i, 0) = a0 - Lfc_Uc_(i, 0) - B_(i, 0);
    g(i, 1) = a1 - Lfc_Uc_(i, 1) - B_(i, 1);
    g(i, 2) = a2 - Lfc_Uc_(i, 2) - B_(i, 2);
  }
  return g_;
}

Eigen::MatrixXd LocalGlobalProblem::solve(const Eigen::MatrixXd& r) const {
  ++solves_;
  return data_.solver.solve(r);
}

// Differentiating R^T S = P (symmetric) along dS with dR = R [omega]_x gives
//   (tr(P) I - P) omega = axial(R^T dS - dS^T R),
// since [omega]_x P + P [omega]_x = [(tr(P) I - P) omega]_x for symmetric P. At a maximizer of tr(R^T S)
// M = tr(P) I - P is positive semi-definite; where it is nearly singular the rotation is ill-determined and
// its derivative unbounded, so M's eigenvalues are floored at kFloor x its largest (a model with less
// negative curvature there, which the step's line search covers).
void LocalGlobalProblem::prepare_hessian() {
  constexpr double kFloor = 1e-6;
  cell_covariances(data_.elements, U_rows_, S_); // U_rows_ holds the last local step's positions
  const auto n = static_cast<int>(S_.size());
  M_inverse_.resize(S_.size());
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    const auto c = static_cast<size_t>(k);
    const Eigen::Matrix3d& R = data_.R[c];
    Eigen::Matrix3d P = R.transpose() * S_[c];
    P = 0.5 * (P + P.transpose()).eval();
    const Eigen::Matrix3d M = P.trace() * Eigen::Matrix3d::Identity() - P;
    // Usually M is safely positive definite and the floor inactive: positive leading minors (Sylvester) and
    // det M >= kFloor tr(M)^3 give lambda_min >= det / lambda_max^2 >= kFloor lambda_max (lambda_max <= tr M),
    // so the adjugate inverts it exactly, far cheaper than the eigendecomposition below (which took 6% of the
    // instructions of a Newton solve on the bunny).
    Eigen::Matrix3d adjugate;
    adjugate << M(1, 1) * M(2, 2) - M(1, 2) * M(2, 1), M(0, 2) * M(2, 1) - M(0, 1) * M(2, 2),
        M(0, 1) * M(1, 2) - M(0, 2) * M(1, 1), M(1, 2) * M(2, 0) - M(1, 0) * M(2, 2),
        M(0, 0) * M(2, 2) - M(0, 2) * M(2, 0), M(0, 2) * M(1, 0) - M(0, 0) * M(1, 2),
        M(1, 0) * M(2, 1) - M(1, 1) * M(2, 0), M(0, 1) * M(2, 0) - M(0, 0) * M(2, 1),
        M(0, 0) * M(1, 1) - M(0, 1) * M(1, 0);
    const double det = M(0, 0) * adjugate(0, 0) + M(0, 1) * adjugate(1, 0) + M(0, 2) * adjugate(2, 0);
    const double trace = M.trace();
    if (M(0, 0) > 0 && adjugate(2, 2) > 0 && det > 0 && det >= kFloor * trace * trace * trace) {
      M_inverse_[c] = adjugate / det;
      continue;
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(M);
    const Eigen::Vector3d lambda = eigen.eigenvalues();
    const double top = lambda.cwiseAbs().maxCoeff();
    if (!(top > 0) || !std::isfinite(top)) { // a cell without deformation signal: no rotation term
      M_inverse_[c].setZero();
      continue;
    }
    const Eigen::Vector3d inverse = lambda.cwiseMax(kFloor * top).cwiseInverse();
    M_inverse_[c] = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  }
}

// H v = L v - rhs(dR[v]) at the free rows: g(U) = L U - rhs(R(U)) (Eq. 14, 16) differentiated, with dR_c from
// dS_c = sum_e w_e (v^T b_e) s_hat_e^T (the covariance sweep run on v) through the relation above.
Eigen::MatrixXd LocalGlobalProblem::hessian_product(const Eigen::MatrixXd& v) {
  // Only the free rows are written, so the constrained ones stay at the zero they got once.
  if (v_rows_.rows() != U_.rows())
    v_rows_.setZero(U_.rows(), 3);
  for (Eigen::Index i = 0; i < free_count(); ++i)
    v_rows_.row(free_row_(i)) = v.row(i);
  cell_covariances(data_.elements, v_rows_, S_); // dS_c, in the Hessian's workspace
  const auto n = static_cast<int>(S_.size());
  dR_.resize(S_.size());
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    const auto c = static_cast<size_t>(k);
    const Eigen::Matrix3d& R = data_.R[c];
    const Eigen::Matrix3d A = R.transpose() * S_[c];
    const Eigen::Vector3d a(A(2, 1) - A(1, 2), A(0, 2) - A(2, 0), A(1, 0) - A(0, 1));
    const Eigen::Vector3d w = M_inverse_[c] * a;
    Eigen::Matrix3d W;
    W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    dR_[c] = R * W;
  }
  arap_rhs_in_visit_order(data_.elements, dR_, d_rhs_);
  Eigen::MatrixXd Hv = L_free_cols_.transpose() * v_rows_;
  for (Eigen::Index i = 0; i < free_count(); ++i)
    Hv.row(i) -= d_rhs_.row(free_row_(i));
  return Hv;
}

} // namespace iarap::detail
