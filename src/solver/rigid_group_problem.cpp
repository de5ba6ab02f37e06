#include "rigid_group_problem.h"

#include "iarap/core/errors.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "iarap/solver/polar_rotation.h"

#include "rigid_groups.h"
#include "soft_terms.h"

#include <algorithm>
#include <string>

namespace iarap::detail {

namespace {

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& X, const std::vector<int>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), X.cols());
  for (size_t k = 0; k < rows.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = X.row(rows[k]);
  return out;
}

// Row i of A U for the symmetric A (its column i).
Eigen::RowVector3d row_times(const Eigen::SparseMatrix<double>& A, int i, const Eigen::MatrixXd& U) {
  Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
  for (Eigen::SparseMatrix<double>::InnerIterator it(A, i); it; ++it) sum += it.value() * U.row(it.row());
  return sum;
}

} // namespace

RigidGroupProblem::RigidGroupProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                                     const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces)
    : data_(data), U_(U), A_(with_soft(data.L, data.Q)) {
  const RigidGroupSystem& rigid = data.rigid;
  const Eigen::Index n = data.V.rows();
  for (Eigen::Index k = 0; k < data.fixed.size(); ++k) U.row(data.fixed(k)) = targets.row(k);
  terms_ = quadratic_terms(data, soft_targets, forces, nullptr);
  s_.setZero(n, 3);
  std::vector<int> every_vertex(static_cast<size_t>(n));
  for (Eigen::Index v = 0; v < n; ++v) every_vertex[static_cast<size_t>(v)] = static_cast<int>(v);
  for (const auto& term : terms_) term->add_linear(every_vertex, s_);

  const double extent = (data.V.colwise().maxCoeff() - data.V.colwise().minCoeff()).norm();
  const size_t groups = rigid.groups.size();
  q_.setZero(n, 3);
  R_g_.resize(groups);
  K_g_.resize(groups);
  t_g_.resize(groups);
  for (size_t g = 0; g < groups; ++g) {
    const std::vector<int>& members = rigid.groups[g];
    const std::vector<int>& held = rigid.held[g];
    // o_g: the rest centroid, the pivot, or the held members' rest centroid (their fit's centre).
    const std::vector<int>& centre = held.empty() ? members : held;
    const Eigen::RowVector3d o = rows_of(data.V, centre).colwise().mean();
    for (const int i : members) q_.row(i) = data.V.row(i) - o;
    const Eigen::MatrixXd moved = rows_of(U, centre);
    t_g_[g] = moved.colwise().mean().transpose();
    // Fitted to the guess (Free, Pivot: the members' rows about t) or to the held members' targets.
    R_g_[g] = best_rotation(
        rows_of(q_, centre.size() > 1 ? centre : members),
        (rows_of(U, centre.size() > 1 ? centre : members).rowwise() - t_g_[g].transpose()), data.planar);
    if (rigid.kind[g] == RigidGroupKind::Held) {
      double off = 0.0;
      for (const int i : held)
        off = std::max(off, (R_g_[g] * q_.row(i).transpose() + t_g_[g] - U.row(i).transpose()).norm());
      if (off > 1e-9 * extent)
        throw InputError(
            "ARAP: the targets of rigid group " + std::to_string(g) + "'s " + std::to_string(held.size()) +
            " constrained vertices are not a rigid motion of their rest positions: the best "
            "rigid fit is " +
            std::to_string(off) + " off (more than 1e-9 of the diagonal " + std::to_string(extent) + ")");
    }
    Eigen::Matrix3d K = Eigen::Matrix3d::Zero(); // sum_{i,j in g} A_ij q_j q_i^T
    for (const int i : members)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A_, i); it; ++it)
        if (rigid.group_of(it.row()) == static_cast<int>(g))
          K += it.value() * q_.row(it.row()).transpose() * q_.row(i);
    K_g_[g] = K;
  }
  y_.resize(rigid.P.cols(), 3);
  for (Eigen::Index v = 0; v < n; ++v)
    if (rigid.unknown_of(v) >= 0) y_.row(rigid.unknown_of(v)) = U.row(v);
  for (size_t g = 0; g < groups; ++g)
    if (rigid.group_unknown(static_cast<Eigen::Index>(g)) >= 0)
      y_.row(rigid.group_unknown(static_cast<Eigen::Index>(g))) = t_g_[g].transpose();
  place_groups();
  data.R.clear(); // the first fit starts cold, as LocalGlobalProblem's
}

void RigidGroupProblem::place_groups() {
  const RigidGroupSystem& rigid = data_.rigid;
  for (Eigen::Index v = 0; v < U_.rows(); ++v)
    if (rigid.unknown_of(v) >= 0) U_.row(v) = y_.row(rigid.unknown_of(v));
  for (size_t g = 0; g < rigid.groups.size(); ++g) {
    const int unknown = rigid.group_unknown(static_cast<Eigen::Index>(g));
    if (unknown >= 0) t_g_[g] = y_.row(unknown).transpose();
    for (const int i : rigid.groups[g]) U_.row(i) = (R_g_[g] * q_.row(i).transpose() + t_g_[g]).transpose();
  }
}

void RigidGroupProblem::set_positions(const Eigen::MatrixXd& y) {
  y_ = y;
  place_groups();
}

void RigidGroupProblem::fit_group_rotations() {
  const RigidGroupSystem& rigid = data_.rigid;
  for (size_t g = 0; g < rigid.groups.size(); ++g) {
    if (rigid.kind[g] == RigidGroupKind::Held) continue; // its targets decide it
    Eigen::Matrix3d M = R_g_[g] * K_g_[g];
    for (const int i : rigid.groups[g]) // U as the groups before this one left it (Gauss-Seidel)
      M -= (row_times(A_, i, U_) - b_.row(i)).transpose() * q_.row(i);
    R_g_[g] = data_.planar ? planar_rotation(M) : polar_rotation(M);
    for (const int i : rigid.groups[g]) U_.row(i) = (R_g_[g] * q_.row(i).transpose() + t_g_[g]).transpose();
  }
}

double RigidGroupProblem::local_step() {
  if (have_b_) fit_group_rotations();
  have_b_ = false; // b_ is of the cell rotations about to be replaced
  double total = fit_rotations(data_.elements, U_, U_rows_, data_.R, cell_energy_);
  if (!terms_.empty()) term_rows_ = U_; // the terms read U row-major in the file's order
  for (const auto& term : terms_) total += term->energy(term_rows_);
  return total;
}

void RigidGroupProblem::assemble_rhs() {
  arap_rhs(data_.elements, data_.R, b_);
  b_ += s_;
  const Eigen::SparseMatrix<double>& P = data_.rigid.P;
  g_ = P.transpose() * (A_ * U_ - b_);
  const Eigen::MatrixXd U_R = U_ - P * y_; // the part of U that y does not move
  B_ = P.transpose() * (b_ - A_ * U_R);
  have_b_ = true;
}

const Eigen::MatrixXd& RigidGroupProblem::plain_step() {
  ++solves_;
  data_.rigid.solver.solve(B_, X_);
  return X_;
}

Eigen::MatrixXd RigidGroupProblem::solve(const Eigen::MatrixXd& r) const {
  ++solves_;
  return data_.rigid.solver.solve(r);
}

void RigidGroupProblem::prepare_hessian() {
  throw SolverError("ARAP: rigid groups have no Hessian (their map is nonlinear in the group rotation)");
}

Eigen::MatrixXd RigidGroupProblem::hessian_product(const Eigen::MatrixXd& /*v*/) {
  prepare_hessian();
  return {};
}

} // namespace iarap::detail
