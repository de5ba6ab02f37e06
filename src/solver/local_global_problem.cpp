#include "local_global_problem.h"

#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"

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
      L_free_cols_.innerIndexPtr()[k] = static_cast<int>(it.row());
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

Eigen::MatrixXd LocalGlobalProblem::positions() const {
  Eigen::MatrixXd x(free_count(), 3);
  for (Eigen::Index i = 0; i < free_count(); ++i)
    x.row(i) = U_.row(data_.free(i));
  return x;
}

void LocalGlobalProblem::set_positions(const Eigen::MatrixXd& x) {
  for (Eigen::Index i = 0; i < free_count(); ++i)
    U_.row(data_.free(i)) = x.row(i);
}

double LocalGlobalProblem::local_step() {
  return fit_rotations(data_.elements, U_, U_rows_, data_.R, cell_energy_);
}

void LocalGlobalProblem::assemble_rhs() {
  arap_rhs(data_.elements, data_.R, rhs_); // Eq. 16
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < free_count(); ++i)
    B_.row(i) = rhs_.row(data_.free(i)) - Lfc_Uc_.row(i);
}

const Eigen::MatrixXd& LocalGlobalProblem::plain_step() {
  data_.solver.solve(B_, X_); // three coordinates at once
  return X_;
}

Eigen::MatrixXd LocalGlobalProblem::gradient() const {
  // (L U)_f - rhs_f = L_ff x + L_fc U_c - rhs_f = L_ff x - B, in one pass over the free rows of L (Eigen's
  // product made a pass per coordinate and two temporaries), parallel over rows as Eigen's was.
  const Eigen::Index nf = free_count();
  Eigen::MatrixXd g(nf, 3);
  const int* outer = L_free_cols_.outerIndexPtr();
  const int* row = L_free_cols_.innerIndexPtr();
  const double* value = L_free_cols_.valuePtr();
  const double *u0 = U_.col(0).data(), *u1 = U_.col(1).data(), *u2 = U_.col(2).data();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < nf; ++i) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0;
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      a0 += value[k] * u0[row[k]];
      a1 += value[k] * u1[row[k]];
      a2 += value[k] * u2[row[k]];
    }
    g(i, 0) = a0 - Lfc_Uc_(i, 0) - B_(i, 0);
    g(i, 1) = a1 - Lfc_Uc_(i, 1) - B_(i, 1);
    g(i, 2) = a2 - Lfc_Uc_(i, 2) - B_(i, 2);
  }
  return g;
}

Eigen::MatrixXd LocalGlobalProblem::solve(const Eigen::MatrixXd& r) const {
  return data_.solver.solve(r);
}

} // namespace iarap::detail
