#include "local_global_problem.h"

#include "iarap/core/resident_memory.h"

#include "streamed_fit_rotations.h"
#include "streamed_layout.h"
#include "streamed_rhs.h"
#include "visit_order.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap::detail {

LocalGlobalProblem::LocalGlobalProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                                       const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces,
                                       double rotation_smoothing, bool warm_start_rotations)
    : data_(data), U_(U), rows_(free_row_system(data)), free_position_(rows_->free_position),
      free_index_(rows_->free_index), L_row_start_(rows_->row_start), L_column_(rows_->column),
      position_(rows_->position), L_value_(rows_->value), gather_(data.solver.gather_rows(free_index_)) {
  // Constrained positions in L_fc's column order: targets, then pinned vertices where the guess has them.
  Eigen::MatrixXd U_c(data.fixed.size() + data.pinned.size(), 3);
  U_c.topRows(data.fixed.size()) = targets;
  for (Eigen::Index k = 0; k < data.pinned.size(); ++k)
    U_c.row(data.fixed.size() + k) = U.row(data.pinned(k));
  for (Eigen::Index k = 0; k < data.fixed.size(); ++k) U.row(data.fixed(k)) = targets.row(k);
  const ArapElements& el = data.elements;
  visit_rows(el, U, U_rows_);
  // U_rows_ holds all of U (its constrained rows too): the caller's copy is released until the destructor
  // writes the result back, one #V x 3 array less at the solve's peak (issue 44). Nothing the iterations
  // call reads U (arap_solve: an on_iteration callback should not read it); a constructor that throws runs
  // no destructor, so the rest writes U back itself then.
  U_ = Eigen::MatrixXd();
  try {
    const std::vector<int>& position = position_;
    const Eigen::Index nf = data.free.size();
    {
      const Eigen::MatrixXd Lfc_Uc_free = data.L_fc * U_c; // rows in data.free's order
      // The terms' linear parts at the free rows, s_f = sum_t s_t, folded into L_fc U_c (B = rhs_f + s_f -
      // L_fc U_c) and kept for the gradient.
      terms_ = quadratic_terms(data, soft_targets, forces, &position_);
      if (terms_.empty()) {
        keep_nonzero_rows(Lfc_Uc_free, &free_index_);
      } else {
        Eigen::MatrixXd Lfc_Uc(nf, 3); // rows of x
        for (Eigen::Index r = 0; r < nf; ++r)
          Lfc_Uc.row(r) = Lfc_Uc_free.row(free_index_[static_cast<size_t>(r)]);
        std::vector<int> unknown(position.size(), -1); // each vertex's row of x
        for (Eigen::Index r = 0; r < nf; ++r)
          unknown[static_cast<size_t>(data.free(free_index_[static_cast<size_t>(r)]))] = static_cast<int>(r);
        linear_f_.setZero(nf, 3);
        for (const auto& term : terms_) term->add_linear(unknown, linear_f_);
        Lfc_Uc -= linear_f_;
        keep_nonzero_rows(Lfc_Uc, nullptr);
      }
    }
    if (data.soft.hard_faces.size() > 0) set_up_hard_points(soft_targets);
    if (rotation_smoothing > 0) {
      if (data.planar)
        throw InputError("ARAP: rotation_smoothing is not supported on planar data (rotations about z only); "
                         "solve the mesh in 3D or use rotation_smoothing 0");
      smoothing_ =
          std::make_unique<RotationSmoothing>(el, position_, rotation_smoothing, rest_area(data.V, data.F));
    }
    B_.resize(nf, 3);
    // The first fit starts cold (fit_rotations warm-starts from rotations it is given): a solve's result then
    // depends on its inputs only, bit for bit, not on what earlier solves left in data.R. Warm, it starts
    // from those, in visit order as the fits keep them.
    if (warm_start_rotations && !smoothing_ && data.R.size() == static_cast<size_t>(el.num_cells)) {
      to_visit_order_in_place(streamed(el).visit_order, data.R);
    } else {
      data.R.clear();
    }
  } catch (...) {
    write_back_positions();
    throw;
  }
}

// C x = d for the hard points (the last of data.soft's points): the corners that are unknowns give C's
// columns (rows of x), the constrained ones (targets, pinned guesses) move to d. Contradictory points throw
// HardPointConflict before any iteration; the initial guess is then moved onto the constraints.
void LocalGlobalProblem::set_up_hard_points(const Eigen::MatrixXd& soft_targets) {
  const Eigen::Index first = data_.soft.soft_size(), m = data_.soft.hard_faces.size();
  // Y = A^{-1} C^T is dense, #free x #points: refuse what would take over 1 GiB rather than swap.
  if (static_cast<double>(m) * static_cast<double>(free_count()) * sizeof(double) > 1073741824.0)
    throw InputError(
        "ARAP: " + std::to_string(m) + " hard points on a mesh of " + std::to_string(free_count()) +
        " free vertices need " +
        std::to_string(static_cast<double>(m) * static_cast<double>(free_count()) * 8 / 1048576) +
        " MiB of dense columns; give fewer, or make them soft with a large weight");
  std::vector<int> row_of_free(free_index_.size(), -1);
  for (size_t r = 0; r < free_index_.size(); ++r)
    row_of_free[static_cast<size_t>(free_index_[r])] = static_cast<int>(r);
  const std::vector<SoftPoint> points = soft_points(data_.soft, data_.F);
  std::vector<ConstraintRow> rows(static_cast<size_t>(m));
  hard_d_.resize(m, 3);
  for (Eigen::Index k = 0; k < m; ++k) {
    const SoftPoint& p = points[static_cast<size_t>(first + k)];
    ConstraintRow& row = rows[static_cast<size_t>(k)];
    hard_d_.row(k) = soft_targets.row(first + k);
    for (int j = 0; j < 3; ++j) {
      const int i = data_.free_slot(p.v[j]);
      row.column[j] = i >= 0 ? row_of_free[static_cast<size_t>(i)] : -1;
      row.c[j] = p.c[j];
      if (i < 0) hard_d_.row(k) -= p.c[j] * U_rows_.row(position_[static_cast<size_t>(p.v[j])]);
    }
  }
  hard_ = HardPointProjection(std::move(rows), free_count(),
                              [this](const Eigen::MatrixXd& b) { return solve_unconstrained(b); });
  // Agreement is judged at 1e-9 of the scene's extent: targets that differ by rounding do not conflict.
  const double extent = (data_.V.colwise().maxCoeff() - data_.V.colwise().minCoeff()).norm() +
                        soft_targets.cwiseAbs().maxCoeff();
  if (const auto conflict = hard_.find_conflict(hard_d_, 1e-9 * extent)) {
    const auto name = [&](Eigen::Index k) {
      return "hard face point [" + std::to_string(k) + "] (face " + std::to_string(data_.soft.hard_faces(k)) +
             ")";
    };
    const std::string with = conflict->depends_on >= 0
                                 ? name(conflict->depends_on) + " and the fixed vertices"
                                 : "the fixed vertices";
    throw HardPointConflict(conflict->row, conflict->depends_on, conflict->gap,
                            "ARAP: " + name(conflict->row) + " contradicts " + with +
                                ": it is a combination of theirs but its target is " +
                                std::to_string(conflict->gap) + " off what they impose on it");
  }
  Eigen::MatrixXd x = positions();
  hard_.correct(x, hard_d_);
  set_positions(x);
}

// Lfc_Uc_ and Lfc_Uc_row_ from the dense rows (row r of x is row (*row_of)[r] of Lfc_Uc, or row r without
// row_of): those with an entry other than +0.0 (a -0.0 is kept, as rhs - (-0.0) and rhs - 0.0 differ for rhs
// = -0.0). Without terms they are the rows beside constrained vertices, a small part of all.
void LocalGlobalProblem::keep_nonzero_rows(const Eigen::MatrixXd& Lfc_Uc, const std::vector<int>* row_of) {
  const auto is_plus_zero = [](double v) { return v == 0.0 && !std::signbit(v); };
  const auto source = [&](Eigen::Index r) {
    return row_of ? static_cast<Eigen::Index>((*row_of)[static_cast<size_t>(r)]) : r;
  };
  Lfc_Uc_row_.clear();
  for (Eigen::Index r = 0; r < Lfc_Uc.rows(); ++r) {
    const Eigen::Index q = source(r);
    if (!is_plus_zero(Lfc_Uc(q, 0)) || !is_plus_zero(Lfc_Uc(q, 1)) || !is_plus_zero(Lfc_Uc(q, 2)))
      Lfc_Uc_row_.push_back(static_cast<int>(r));
  }
  Lfc_Uc_.resize(static_cast<Eigen::Index>(Lfc_Uc_row_.size()), 3);
  for (size_t k = 0; k < Lfc_Uc_row_.size(); ++k)
    Lfc_Uc_.row(static_cast<Eigen::Index>(k)) = Lfc_Uc.row(source(Lfc_Uc_row_[k]));
}

LocalGlobalProblem::~LocalGlobalProblem() {
  trace_resident("solve's workspaces"); // the solve's high-water mark, before they go
  // The workspaces go before U comes back, so that its array does not add to their peak.
  for (Eigen::MatrixXd* m : {&B_, &g_, &b_free_, &linear_f_}) *m = Eigen::MatrixXd();
  cell_energy_ = Eigen::VectorXd();
  v_rows_ = ArapElements::ValueRows();
  for (std::vector<Eigen::Matrix3d>* v : {&S_, &dS_, &M_inverse_, &dR_})
    std::vector<Eigen::Matrix3d>().swap(*v);
  write_back_positions();
  if (data_.R.size() != static_cast<size_t>(data_.elements.num_cells)) return; // no local step ran
  from_visit_order_in_place(streamed(data_.elements).visit_order, data_.R);
}

// U from U_rows_, every row: the free ones the iterations moved, the constrained ones as the constructor set
// them (targets, pinned guesses).
void LocalGlobalProblem::write_back_positions() {
  const std::vector<int>& order = streamed(data_.elements).visit_order;
  U_.resize(U_rows_.rows(), 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index p = 0; p < U_rows_.rows(); ++p)
    for (int d = 0; d < 3; ++d) U_(order[static_cast<size_t>(p)], d) = U_rows_(p, d);
}

Eigen::MatrixXd LocalGlobalProblem::positions() const {
  Eigen::MatrixXd x(free_count(), 3);
  for (Eigen::Index r = 0; r < free_count(); ++r)
    x.row(r) = U_rows_.row(free_position_[static_cast<size_t>(r)]);
  return x;
}

void LocalGlobalProblem::set_positions(const Eigen::MatrixXd& x) {
  covariances_current_ = false;
#pragma omp parallel for schedule(static)
  for (Eigen::Index r = 0; r < free_count(); ++r)
    U_rows_.row(free_position_[static_cast<size_t>(r)]) = x.row(r);
}

double LocalGlobalProblem::local_step() {
  double total = 0.0;
  if (smoothing_) { // the coupled fit: from the covariances, all rotations at once (rotation_smoothing.h)
    cell_covariances(data_.elements, U_rows_, S_);
    smoothing_->fit(S_, data_.R);
    total = cell_energies_in_visit_order(data_.elements, U_rows_, data_.R, cell_energy_) +
            smoothing_->energy(data_.R);
  } else {
    total = fit_rotations_in_visit_order(data_.elements, U_rows_, data_.R, cell_energy_,
                                         keep_covariances_ ? &S_ : nullptr);
  }
  covariances_current_ = keep_covariances_;
  for (const auto& term : terms_) total += term->energy(U_rows_);
  return total;
}

namespace {
// Row r of L (the flat CSR of LocalGlobalProblem) times the rows of u (#V x 3, row-major, visit order).
inline void L_row_times(const int* start, const int* column, const double* value, int r, const double* u,
                        double (&out)[3]) {
  double a0 = 0.0, a1 = 0.0, a2 = 0.0;
  for (int k = start[r]; k < start[r + 1]; ++k) {
    const double* ur = u + 3 * column[k];
    a0 += value[k] * ur[0];
    a1 += value[k] * ur[1];
    a2 += value[k] * ur[2];
  }
  out[0] = a0, out[1] = a1, out[2] = a2;
}
} // namespace

void LocalGlobalProblem::assemble_rhs() {
  assemble(true);
}

double LocalGlobalProblem::assemble_rhs_gradient_norm() {
  if (!hard_.empty()) { // the norm of the projected gradient
    assemble(true);
    return g_.norm();
  }
  return std::sqrt(assemble(false));
}

// B = rhs_f - L_fc U_c (Eq. 16) and g = (L U)_f - rhs_f = L_ff x - B (Eq. 14 at the free rows), streamed
// over the free vertices in visit order: the rotations' terms and L's rows are read once, in order. With
// soft constraints and forces Lfc_Uc_ holds L_fc U_c - s_f - f_f and L is L + Q: g = (L + Q) U - rhs - s -
// f at the free rows. Without store_gradient g_ is left empty and |g|^2 returned, summed in blocks of rows
// whatever the thread count (the same bits at every count); with it, 0.
double LocalGlobalProblem::assemble(bool store_gradient) {
  constexpr int kBlock = 4096;
  const auto rows = static_cast<int>(free_position_.size());
  const int blocks = (rows + kBlock - 1) / kBlock;
  B_.resize(free_count(), 3);
  if (store_gradient)
    g_.resize(free_count(), 3);
  else
    g_.resize(0, 3);
  B_holds_step_ = false;
  std::vector<double> block_squares(store_gradient ? 0 : static_cast<size_t>(blocks));
  const double* u = U_rows_.data();
  const StreamedLayout& sl = streamed(data_.elements);
  const bool linear = !terms_.empty();
  const auto kept_rows = static_cast<std::ptrdiff_t>(Lfc_Uc_row_.size());
#pragma omp parallel for schedule(static)
  for (int block = 0; block < blocks; ++block) {
    // The rows of a block, walking the kept rows of L_fc U_c beside them (0 elsewhere).
    const int first = block * kBlock, last = std::min(rows, first + kBlock);
    std::ptrdiff_t slot =
        std::lower_bound(Lfc_Uc_row_.begin(), Lfc_Uc_row_.end(), first) - Lfc_Uc_row_.begin();
    double squares = 0.0;
    for (int r = first; r < last; ++r) {
      double rhs[3], LU[3], Lfc_Uc[3] = {0.0, 0.0, 0.0};
      if (slot < kept_rows && Lfc_Uc_row_[static_cast<size_t>(slot)] == r) {
        for (int d = 0; d < 3; ++d) Lfc_Uc[d] = Lfc_Uc_(slot, d);
        ++slot;
      }
      arap_rhs_row(sl, data_.R, free_position_[static_cast<size_t>(r)], rhs);
      L_row_times(L_row_start_.data(), L_column_.data(), L_value_.data(), r, u, LU);
      for (int d = 0; d < 3; ++d) {
        B_(r, d) = rhs[d] - Lfc_Uc[d];
        double g = LU[d] - Lfc_Uc[d] - B_(r, d);
        if (linear) g -= linear_f_(r, d);
        if (store_gradient)
          g_(r, d) = g;
        else
          squares += g * g;
      }
    }
    if (!store_gradient) block_squares[static_cast<size_t>(block)] = squares;
  }
  if (store_gradient) {
    hard_.project_gradient(g_);
    return 0.0;
  }
  double total = 0.0;
  for (const double s : block_squares) total += s;
  return total;
}

const Eigen::MatrixXd& LocalGlobalProblem::plain_step() {
  // G overwrites B (B's rows are gathered into the factor's order before any of G's is written): one
  // #free x 3 array fewer at a solve's peak (issue 44). Asked again, the same G.
  if (!B_holds_step_) {
    solve_into(B_, B_);
    hard_.correct(B_, hard_d_);
    B_holds_step_ = true;
  }
  return B_;
}

Eigen::MatrixXd LocalGlobalProblem::solve(const Eigen::MatrixXd& r) const {
  Eigen::MatrixXd x;
  solve_into(r, x);
  hard_.project(x);
  return x;
}

Eigen::MatrixXd LocalGlobalProblem::solve_unconstrained(const Eigen::MatrixXd& r) const {
  Eigen::MatrixXd x;
  solve_into(r, x);
  return x;
}

// The factor's rows follow data.free; x's follow the visit order: the supernodal solve gathers them
// through gather_ (x may be b); other factorizations get rows permuted on the way in and out (all of b is
// read before x is written).
void LocalGlobalProblem::solve_into(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const {
  ++solves_;
  if (!gather_.empty()) {
    data_.solver.solve_gathered(b, x, gather_);
    return;
  }
  const Eigen::Index nf = free_count();
  const Eigen::Index columns = b.cols();
  b_free_.resize(nf, columns);
#pragma omp parallel for schedule(static)
  for (Eigen::Index r = 0; r < nf; ++r)
    for (Eigen::Index d = 0; d < columns; ++d) b_free_(free_index_[static_cast<size_t>(r)], d) = b(r, d);
  data_.solver.solve(b_free_, b_free_); // all columns at once, in place
  x.resize(nf, columns);
#pragma omp parallel for schedule(static)
  for (Eigen::Index r = 0; r < nf; ++r)
    for (Eigen::Index d = 0; d < columns; ++d) x(r, d) = b_free_(free_index_[static_cast<size_t>(r)], d);
}

// Differentiating R^T S = P (symmetric) along dS with dR = R [omega]_x gives
//   (tr(P) I - P) omega = axial(R^T dS - dS^T R),
// since [omega]_x P + P [omega]_x = [(tr(P) I - P) omega]_x for symmetric P. At a maximizer of tr(R^T S)
// M = tr(P) I - P is positive semi-definite; where it is nearly singular the rotation is ill-determined and
// its derivative unbounded, so M's eigenvalues are floored at kFloor x its largest (a model with less
// negative curvature there, which the step's line search covers).
void LocalGlobalProblem::prepare_hessian() {
  constexpr double kFloor = 1e-6;
  if (smoothing_) { // the local step kept S; H couples the rotations (rotation_smoothing.h)
    smoothing_->prepare_tangent(S_, data_.R);
    return;
  }
  // Else the last local step kept them (a hybrid solve asks for that only from its switch to Newton on).
  if (!covariances_current_)
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
    // det M >= kFloor tr(M)^3 give lambda_min >= det / lambda_max^2 >= kFloor lambda_max (lambda_max <= tr
    // M), so the adjugate inverts it exactly, far cheaper than the eigendecomposition below (which took 6% of
    // the instructions of a Newton solve on the bunny).
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
  if (v_rows_.rows() != U_rows_.rows()) v_rows_.setZero(U_rows_.rows(), 3);
  for (Eigen::Index r = 0; r < free_count(); ++r)
    v_rows_.row(free_position_[static_cast<size_t>(r)]) = v.row(r);
  cell_covariances(data_.elements, v_rows_, dS_); // dS_c
  const auto n = static_cast<int>(dS_.size());
  dR_.resize(dS_.size());
  if (smoothing_) { // omega = H^{-1} a over all cells at once
    tangent_rhs_.resize(dS_.size());
#pragma omp parallel for schedule(static)
    for (int k = 0; k < n; ++k)
      tangent_rhs_[static_cast<size_t>(k)] =
          vee_of_skew_part(data_.R[static_cast<size_t>(k)].transpose() * dS_[static_cast<size_t>(k)]);
    smoothing_->tangent_solve(tangent_rhs_, tangent_omega_);
  }
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    const auto c = static_cast<size_t>(k);
    const Eigen::Matrix3d& R = data_.R[c];
    const Eigen::Vector3d w = smoothing_
                                  ? tangent_omega_[c]
                                  : Eigen::Vector3d(M_inverse_[c] * vee_of_skew_part(R.transpose() * dS_[c]));
    Eigen::Matrix3d W;
    W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    dR_[c] = R * W;
  }
  Eigen::MatrixXd Hv(free_count(), 3);
  const auto rows = static_cast<int>(free_position_.size());
  const double* vr = v_rows_.data();
  const StreamedLayout& sl = streamed(data_.elements);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < rows; ++r) {
    double d_rhs[3], Lv[3];
    arap_rhs_row(sl, dR_, free_position_[static_cast<size_t>(r)], d_rhs);
    L_row_times(L_row_start_.data(), L_column_.data(), L_value_.data(), r, vr, Lv);
    for (int d = 0; d < 3; ++d) Hv(r, d) = Lv[d] - d_rhs[d];
  }
  return Hv;
}

} // namespace iarap::detail
