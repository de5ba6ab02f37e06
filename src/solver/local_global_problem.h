// The local/global ARAP problem on the free vertices' positions x (#free x 3), as the loops of arap_solve
// (plain, Anderson, L-BFGS) see it: the energy E(x) = min_R energy with its rotations (local step), the
// right-hand side B(x) = rhs_f(R*(x)) - L_fc U_c (Eq. 16), the plain iterate G(x) = L_ff^{-1} B(x) (global
// step) and the gradient g(x) = L_ff x - B(x) = L_ff (x - G(x)) (Eq. 14 at the free rows, by the envelope
// theorem). With the quadratic terms of quadratic_terms.h (soft points, forces) every piece is of the total
// E + sum_t E_t: L stands for L + Q (in L_ff, L_fc and the Hessian), B gains the terms' linear parts s_t at
// the free rows and local_step() returns the total, so that every optimizer minimizes it. With hard points (C
// x = d, hard_points.h) x stays on the constraints: the initial guess is moved onto them, plain_step is the
// constrained global step, solve() maps onto their tangent space and the gradient is projected so that its
// preconditioned step keeps them (zero at the constrained minimum): the loops need not know. Internal to the
// solver; the public contract is arap_solve's.
#pragma once
#include "iarap/solver/arap_types.h"

#include "free_row_system.h"
#include "hard_points.h"
#include "inner.h"
#include "problem.h"
#include "quadratic_terms.h"
#include "rotation_smoothing.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace iarap::detail {

class LocalGlobalProblem final : public Problem {
public:
  // Sets U's constrained rows (targets at data.fixed, U's own rows at data.pinned) and precomputes
  // L_fc U_c and the free rows of L. data and U must outlive the problem. While it lives the positions and
  // data.R are kept in the elements' visit order (ArapElements::visit_order), and so are the rows of x, B,
  // g and every #free x 3 matrix of this interface (the free vertices in visit order: the passes over them
  // stream); the destructor writes U and data.R back in the file's order. soft_targets: #soft x 3 targets
  // of data.soft's points (ArapSoftConstraints::size rows; data.Q must be of data.soft). forces: #V x 3
  // external forces f (0 x 0: none; ArapSolveOptions::forces). Both become quadratic terms.
  // rotation_smoothing: ALPHA >= 0 of ArapSolveOptions::rotation_smoothing; above 0 the rotations are
  // coupled (rotation_smoothing.h): the local step solves for all of them at once and its energy includes
  // E_smooth. Throws InputError for planar data and for tetrahedral ARAP with ALPHA > 0.
  // warm_start_rotations: ArapSolveOptions::warm_start_rotations (data.R, one rotation per cell in the
  // file's order, starts the first fit; ignored with ALPHA > 0).
  LocalGlobalProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                     const Eigen::MatrixXd& soft_targets = Eigen::MatrixXd(0, 3),
                     const Eigen::MatrixXd& forces = Eigen::MatrixXd(0, 3), double rotation_smoothing = 0.0,
                     bool warm_start_rotations = false);
  ~LocalGlobalProblem() override;
  LocalGlobalProblem(const LocalGlobalProblem&) = delete;
  LocalGlobalProblem& operator=(const LocalGlobalProblem&) = delete;

  Eigen::Index free_count() const override { return data_.free.size(); }
  Eigen::Index dimension() const override { return 3; }
  // x = U's free rows (in visit order).
  Eigen::MatrixXd positions() const override;
  void set_positions(const Eigen::MatrixXd& x) override;

  // Local step at U: fits data.R and returns E(U) + sum_t E_t(U) over the quadratic terms (the penalty P,
  // then the potential -f . (U - V)).
  double local_step() override;
  // B(U) from data.R (the rotations of the last local step), kept for plain_step, and the gradient there
  // (gradient()), in one pass over the free vertices.
  void assemble_rhs() override;
  double assemble_rhs_gradient_norm() override;
  // G = L_ff^{-1} B: the plain local/global iterate from the point assemble_rhs last saw (kept in this
  // object until the next assemble_rhs, in B's place: the solve reuses its workspaces and allocates
  // nothing).
  const Eigen::MatrixXd& plain_step() override;
  // g = L_ff x - B at the point assemble_rhs last saw, computed there (kept until its next call).
  const Eigen::MatrixXd& gradient() const override { return g_; }
  // L_ff^{-1} r (r #free x 3), projected onto the hard points' tangent space when there are any.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const override;

  // The Hessian of E(x) = min_R energy at the point of the last local step, for Newton-type steps:
  // prepare_hessian() keeps per cell M_c^{-1} = (tr(P_c) I - P_c)^{-1} with P_c = R_c^T S_c (what the
  // derivative of the polar rotation needs); hessian_product(v) then returns H v (v #free x 3).
  void prepare_hessian() override;
  // From now on each local step keeps its covariances for prepare_hessian, which then need not sweep the
  // elements again (for loops that prepare the Hessian at most local steps).
  void keep_covariances() override { keep_covariances_ = true; }
  Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v) override;

  // Back-substitutions with the factor so far (plain_step and solve).
  int solves() const override { return solves_; }

private:
  void solve_into(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const;
  double assemble(bool store_gradient);
  Eigen::MatrixXd solve_unconstrained(const Eigen::MatrixXd& r) const;
  void set_up_hard_points(const Eigen::MatrixXd& soft_targets);
  void keep_nonzero_rows(const Eigen::MatrixXd& Lfc_Uc, const std::vector<int>* row_of);
  void write_back_positions();

  ArapData& data_;
  Eigen::MatrixXd& U_;
  // L_fc U_c (less the terms' linear parts) at the free rows, only where a row is not zero: Lfc_Uc_ row k
  // is the row Lfc_Uc_row_[k] (ascending) of x, the others are +0 (issue 44: 24 bytes a free vertex).
  std::vector<int> Lfc_Uc_row_;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Lfc_Uc_;
  // The free rows of the symmetric L in visit order, as flat CSR (free_row_system.h, kept in data between
  // solves): row r belongs to the free vertex at position free_position_[r] (increasing) with free index
  // free_index_[r]; its columns are visit positions. The fused right-hand-side and gradient pass and the
  // Hessian product stream them beside U_rows_. position_: the visit position of each vertex (its row of
  // U_rows_).
  std::shared_ptr<const FreeRowSystem> rows_;
  const std::vector<int>&free_position_, &free_index_, &L_row_start_, &L_column_, &position_;
  const std::vector<double>& L_value_;
  // The supernodal factor's rows in x's row order (SparseCholesky::gather_rows); empty for the other
  // factorizations, which solve through b_free_.
  std::vector<int> gather_;
  ArapElements::ValueRows U_rows_; // the positions in visit order (U's are written back at the end)
  Eigen::VectorXd cell_energy_;
  Eigen::MatrixXd B_, g_;
  bool B_holds_step_ = false; // plain_step has replaced B_ by G (until the next assemble_rhs)
  // Without gather_: a solve's right-hand side and then, solved in place, its solution in the factor's row
  // order.
  mutable Eigen::MatrixXd b_free_;
  std::vector<Eigen::Matrix3d> S_, dS_, M_inverse_, dR_; // Hessian workspaces (per cell)
  bool keep_covariances_ = false;
  bool covariances_current_ = false; // S_ holds the last local step's covariances (kept, or smoothing's)
  ArapElements::ValueRows v_rows_;   // a direction v on all vertices, 0 at constrained ones
  mutable int solves_ = 0;
  std::vector<std::unique_ptr<QuadraticTerm>> terms_; // evaluated on U_rows_
  Eigen::MatrixXd linear_f_; // #free x 3: sum_t s_t at the free rows (visit order), when there are terms
  std::unique_ptr<RotationSmoothing> smoothing_;             // ALPHA > 0 only
  std::vector<Eigen::Vector3d> tangent_rhs_, tangent_omega_; // the coupled dR's system (hessian_product)
  HardPointProjection hard_;                                 // empty without hard points
  Eigen::MatrixXd hard_d_; // #hard x 3: their targets less the constrained corners' share
};

} // namespace iarap::detail
