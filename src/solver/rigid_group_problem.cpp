#include "rigid_group_problem.h"

#include "iarap/core/errors.h"
#include "iarap/solver/arap_rhs.h"
#include "iarap/solver/fit_rotations.h"
#include "iarap/solver/polar_rotation.h"

#include "rigid_groups.h"
#include "rotation_smoothing.h"
#include "rotation_vector.h"
#include "soft_terms.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap::detail {

namespace {

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& X, const std::vector<int>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), X.cols());
  for (size_t k = 0; k < rows.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = X.row(rows[k]);
  return out;
}

// The cell covariances S_c = sum_{e in c} w_e (X^T b_e) s_hat_e^T of positions (or a direction) X, in the
// file's order. Each cell's stiffness factor is left out: it scales S_c and dS_c alike, which neither the
// rotation nor its derivative sees.
void file_order_covariances(const ArapElements& el, const Eigen::MatrixXd& X,
                            std::vector<Eigen::Matrix3d>& S) {
  S.assign(static_cast<size_t>(el.num_cells), Eigen::Matrix3d::Zero());
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) s += el.b_value(e, k) * X.row(el.b_index(e, k)).transpose();
    const Eigen::Matrix3d term = el.w(e) * s * el.s_hat.row(e);
    for (int c = el.cell_start[static_cast<size_t>(e)]; c < el.cell_start[static_cast<size_t>(e) + 1]; ++c)
      S[static_cast<size_t>(el.cell[static_cast<size_t>(c)])] += term;
  }
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
  R0_ = R_g_;
  rotation_row_.assign(groups, -1);
  for (size_t g = 0; g < groups; ++g)
    if (rigid.kind[g] != RigidGroupKind::Held) {
      rotation_row_[g] = static_cast<int>(turning_.size());
      turning_.push_back(static_cast<int>(g));
    }
  w_.setZero(static_cast<Eigen::Index>(turning_.size()), 3);
  axes_ = data.planar ? std::vector<int>{2} : std::vector<int>{0, 1, 2};
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
  J_.resize(turning_.size());
  for (size_t k = 0; k < turning_.size(); ++k) {
    const auto g = static_cast<size_t>(turning_[k]);
    const Eigen::Vector3d w = w_.row(static_cast<Eigen::Index>(k)).transpose();
    R_g_[g] = rotation_of_vector(w) * R0_[g];
    J_[k] = left_jacobian(w);
  }
  preconditioner_stale_ = true;
  for (Eigen::Index v = 0; v < U_.rows(); ++v)
    if (rigid.unknown_of(v) >= 0) U_.row(v) = y_.row(rigid.unknown_of(v));
  for (size_t g = 0; g < rigid.groups.size(); ++g) {
    const int unknown = rigid.group_unknown(static_cast<Eigen::Index>(g));
    if (unknown >= 0) t_g_[g] = y_.row(unknown).transpose();
    for (const int i : rigid.groups[g]) U_.row(i) = (R_g_[g] * q_.row(i).transpose() + t_g_[g]).transpose();
  }
}

Eigen::MatrixXd RigidGroupProblem::positions() const {
  Eigen::MatrixXd x(free_count(), 3);
  x << y_, w_;
  return x;
}

void RigidGroupProblem::set_positions(const Eigen::MatrixXd& x) {
  y_ = x.topRows(y_.rows());
  w_ = x.bottomRows(w_.rows());
  if (data_.planar) w_.leftCols(2).setZero(); // turns about z only
  place_groups();
}

Eigen::RowVector3d RigidGroupProblem::residual_row(const Eigen::MatrixXd& U, int i) const {
  Eigen::RowVector3d sum = -b_.row(i);
  for (Eigen::SparseMatrix<double>::InnerIterator it(A_, i); it; ++it) sum += it.value() * U.row(it.row());
  return sum;
}

double RigidGroupProblem::local_step() {
  double total = fit_rotations(data_.elements, U_, U_rows_, data_.R, cell_energy_);
  if (!terms_.empty()) term_rows_ = U_; // the terms read U row-major in the file's order
  for (const auto& term : terms_) total += term->energy(term_rows_);
  return total;
}

void RigidGroupProblem::assemble_rhs() {
  arap_rhs(data_.elements, data_.R, b_);
  b_ += s_;
  G_ = A_ * U_ - b_;
  U_b_ = U_; // the point of b: plain_step starts there whatever set_positions did since
  R_b_ = R_g_;
  t_b_ = t_g_;
  y_b_ = y_;
  const Eigen::Index ny = y_.rows();
  g_.resize(free_count(), 3);
  g_.topRows(ny) = data_.rigid.P.transpose() * G_;
  torque_.resize(turning_.size());
  for (size_t k = 0; k < turning_.size(); ++k) {
    const auto g = static_cast<size_t>(turning_[k]);
    Eigen::Vector3d tau = Eigen::Vector3d::Zero();
    for (const int i : data_.rigid.groups[g])
      tau += Eigen::Vector3d(R_g_[g] * q_.row(i).transpose()).cross(Eigen::Vector3d(G_.row(i).transpose()));
    torque_[k] = tau;
    g_.row(ny + static_cast<Eigen::Index>(k)) = (J_[k].transpose() * tau).transpose();
  }
  if (data_.planar) g_.bottomRows(w_.rows()).leftCols(2).setZero();
}

const Eigen::MatrixXd& RigidGroupProblem::plain_step() {
  const RigidGroupSystem& rigid = data_.rigid;
  Eigen::MatrixXd U = U_b_;
  std::vector<Eigen::Matrix3d> R = R_b_;
  for (const int group : turning_) { // U as the groups before this one left it (Gauss-Seidel)
    const auto g = static_cast<size_t>(group);
    Eigen::Matrix3d M = R[g] * K_g_[g];
    for (const int i : rigid.groups[g]) M -= residual_row(U, i).transpose() * q_.row(i);
    R[g] = data_.planar ? planar_rotation(M) : polar_rotation(M);
    for (const int i : rigid.groups[g]) U.row(i) = (R[g] * q_.row(i).transpose() + t_b_[g]).transpose();
  }
  const Eigen::MatrixXd U_R = U - rigid.P * y_b_; // the part of U that y does not move
  const Eigen::MatrixXd B = rigid.P.transpose() * (b_ - A_ * U_R);
  X_.resize(free_count(), 3);
  if (y_.rows() > 0) {
    ++solves_;
    X_.topRows(y_.rows()) = rigid.solver.solve(B);
  }
  for (size_t k = 0; k < turning_.size(); ++k) {
    const auto g = static_cast<size_t>(turning_[k]);
    X_.row(y_.rows() + static_cast<Eigen::Index>(k)) =
        rotation_vector_of(R[g] * R0_[g].transpose()).transpose();
  }
  if (data_.planar) X_.bottomRows(w_.rows()).leftCols(2).setZero();
  return X_;
}

Eigen::MatrixXd RigidGroupProblem::turn_field(size_t k, const Eigen::Vector3d& e) const {
  const auto g = static_cast<size_t>(turning_[k]);
  const Eigen::Vector3d turn = J_[k] * e;
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(U_.rows(), 3);
  for (const int i : data_.rigid.groups[g])
    F.row(i) = turn.cross(Eigen::Vector3d(R_g_[g] * q_.row(i).transpose())).transpose();
  return F;
}

void RigidGroupProblem::prepare_preconditioner() const {
  const Eigen::Index ny = y_.rows();
  const size_t columns = turning_.size() * axes_.size();
  std::vector<Eigen::MatrixXd> AF(columns), F(columns); // A T_w's columns, T_w's columns
  std::vector<Eigen::MatrixXd> C(columns);              // P^T A T_w's columns
  Z_.assign(columns, Eigen::MatrixXd());
  for (size_t k = 0; k < turning_.size(); ++k)
    for (size_t a = 0; a < axes_.size(); ++a) {
      const size_t col = k * axes_.size() + a;
      F[col] = turn_field(k, Eigen::Vector3d::Unit(axes_[a]));
      AF[col] = A_ * F[col];
      C[col] = data_.rigid.P.transpose() * AF[col];
      if (ny > 0) {
        ++solves_;
        Z_[col] = data_.rigid.solver.solve(C[col]);
      }
    }
  Eigen::MatrixXd S(static_cast<Eigen::Index>(columns), static_cast<Eigen::Index>(columns));
  for (size_t c = 0; c < columns; ++c)
    for (size_t d = 0; d < columns; ++d) {
      double value = (F[c].array() * AF[d].array()).sum();       // D
      if (ny > 0) value -= (C[c].array() * Z_[d].array()).sum(); // - C^T K^{-1} C
      S(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(d)) = value;
    }
  S = 0.5 * (S + S.transpose()).eval();
  // A turn about the line of collinear members moves nothing: no step along it (pseudo-inverse).
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(S);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  const double top = lambda.size() > 0 ? lambda.cwiseAbs().maxCoeff() : 0.0;
  Eigen::VectorXd inverse = Eigen::VectorXd::Zero(lambda.size());
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
    if (lambda(k) > 1e-12 * top) inverse(k) = 1.0 / lambda(k);
  schur_inverse_ = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  preconditioner_stale_ = false;
}

// [K C; C^T D]^{-1} [r_y; r_w] by blocks: z_w = S^+ (r_w - Z^T r_y), z_y = K^{-1} r_y - Z z_w.
Eigen::MatrixXd RigidGroupProblem::solve(const Eigen::MatrixXd& r) const {
  if (preconditioner_stale_) prepare_preconditioner();
  const Eigen::Index ny = y_.rows();
  const size_t columns = turning_.size() * axes_.size();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(r.rows(), 3);
  const Eigen::MatrixXd r_y = r.topRows(ny);
  Eigen::VectorXd c(static_cast<Eigen::Index>(columns));
  for (size_t k = 0; k < turning_.size(); ++k)
    for (size_t a = 0; a < axes_.size(); ++a) {
      const size_t col = k * axes_.size() + a;
      c(static_cast<Eigen::Index>(col)) = r(ny + static_cast<Eigen::Index>(k), axes_[a]);
      if (ny > 0) c(static_cast<Eigen::Index>(col)) -= (Z_[col].array() * r_y.array()).sum();
    }
  const Eigen::VectorXd z_w = schur_inverse_ * c;
  if (ny > 0) {
    ++solves_;
    Eigen::MatrixXd z_y = data_.rigid.solver.solve(r_y);
    for (size_t col = 0; col < columns; ++col) z_y -= z_w(static_cast<Eigen::Index>(col)) * Z_[col];
    out.topRows(ny) = z_y;
  }
  for (size_t k = 0; k < turning_.size(); ++k)
    for (size_t a = 0; a < axes_.size(); ++a)
      out(ny + static_cast<Eigen::Index>(k), axes_[a]) = z_w(static_cast<Eigen::Index>(k * axes_.size() + a));
  return out;
}

void RigidGroupProblem::prepare_hessian() {
  std::vector<Eigen::Matrix3d> S;
  file_order_covariances(data_.elements, U_, S);
  M_inverse_.resize(S.size());
  for (size_t c = 0; c < S.size(); ++c) {
    Eigen::Matrix3d P = data_.R[c].transpose() * S[c];
    P = 0.5 * (P + P.transpose()).eval();
    M_inverse_[c] = floored_inverse(P.trace() * Eigen::Matrix3d::Identity() - P);
  }
  turn_hessian_.resize(turning_.size());
  for (size_t k = 0; k < turning_.size(); ++k) {
    const auto g = static_cast<size_t>(turning_[k]);
    Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
    for (const int i : data_.rigid.groups[g]) {
      const Eigen::Vector3d r = R_g_[g] * q_.row(i).transpose(), G = G_.row(i).transpose();
      N += 0.5 * (G * r.transpose() + r * G.transpose()) - r.dot(G) * Eigen::Matrix3d::Identity();
    }
    const Eigen::Matrix3d T =
        left_jacobian_transpose_derivative(w_.row(static_cast<Eigen::Index>(k)).transpose(), torque_[k]);
    turn_hessian_[k] = J_[k].transpose() * N * J_[k] + 0.5 * (T + T.transpose());
  }
}

Eigen::MatrixXd RigidGroupProblem::position_change(const Eigen::MatrixXd& v,
                                                   std::vector<Eigen::Vector3d>& turn) const {
  Eigen::MatrixXd V = data_.rigid.P * v.topRows(y_.rows());
  turn.resize(turning_.size());
  for (size_t k = 0; k < turning_.size(); ++k) {
    Eigen::Vector3d v_w = v.row(y_.rows() + static_cast<Eigen::Index>(k)).transpose();
    if (data_.planar) v_w.head(2).setZero();
    turn[k] = J_[k] * v_w;
    V += turn_field(k, v_w);
  }
  return V;
}

// H v = T^T (A V - rhs(dR[V])) + the turns' own curvature, V = T v (the header's formula); dR_c = R_c
// [M_c^{-1} vee(R_c^T dS_c)]x, the derivative of the polar rotation, as in LocalGlobalProblem.
Eigen::MatrixXd RigidGroupProblem::hessian_product(const Eigen::MatrixXd& v) {
  std::vector<Eigen::Vector3d> turn;
  const Eigen::MatrixXd V = position_change(v, turn);
  std::vector<Eigen::Matrix3d> dS;
  file_order_covariances(data_.elements, V, dS);
  dR_.resize(dS.size());
  for (size_t c = 0; c < dS.size(); ++c)
    dR_[c] = data_.R[c] * cross_matrix(M_inverse_[c] * vee_of_skew_part(data_.R[c].transpose() * dS[c]));
  Eigen::MatrixXd d_rhs;
  arap_rhs(data_.elements, dR_, d_rhs);
  const Eigen::MatrixXd HV = A_ * V - d_rhs;
  Eigen::MatrixXd out(v.rows(), 3);
  const Eigen::Index ny = y_.rows();
  out.topRows(ny) = data_.rigid.P.transpose() * HV;
  for (size_t k = 0; k < turning_.size(); ++k) {
    const auto g = static_cast<size_t>(turning_[k]);
    Eigen::Vector3d tau = Eigen::Vector3d::Zero();
    for (const int i : data_.rigid.groups[g])
      tau += Eigen::Vector3d(R_g_[g] * q_.row(i).transpose()).cross(Eigen::Vector3d(HV.row(i).transpose()));
    Eigen::Vector3d v_w = v.row(ny + static_cast<Eigen::Index>(k)).transpose();
    if (data_.planar) v_w.head(2).setZero();
    out.row(ny + static_cast<Eigen::Index>(k)) =
        (J_[k].transpose() * tau + turn_hessian_[k] * v_w).transpose();
  }
  if (data_.planar) out.bottomRows(w_.rows()).leftCols(2).setZero();
  return out;
}

} // namespace iarap::detail
