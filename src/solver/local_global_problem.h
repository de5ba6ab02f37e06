// The local/global ARAP problem on the free vertices' positions x (#free x 3), as the loops of arap_solve
// (plain, Anderson, L-BFGS) see it: the energy E(x) = min_R energy with its rotations (local step), the
// right-hand side B(x) = rhs_f(R*(x)) - L_fc U_c (Eq. 16), the plain iterate G(x) = L_ff^{-1} B(x) (global
// step) and the gradient g(x) = L_ff x - B(x) = L_ff (x - G(x)) (Eq. 14 at the free rows, by the envelope
// theorem). Internal to the solver; the public contract is arap_solve's.
#pragma once
#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace iarap::detail {

class LocalGlobalProblem {
public:
  // Sets U's constrained rows (targets at data.fixed, U's own rows at data.pinned) and precomputes
  // L_fc U_c and the free rows of L. data and U must outlive the problem. While it lives the positions and
  // data.R are kept in the elements' visit order (ArapElements::visit_order; x itself follows data.free);
  // the destructor writes them back to U and data.R in the file's order.
  LocalGlobalProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U);
  ~LocalGlobalProblem();
  LocalGlobalProblem(const LocalGlobalProblem&) = delete;
  LocalGlobalProblem& operator=(const LocalGlobalProblem&) = delete;

  Eigen::Index free_count() const { return data_.free.size(); }
  // x = U's free rows.
  Eigen::MatrixXd positions() const;
  void set_positions(const Eigen::MatrixXd& x);

  // Local step at U: fits data.R and returns E(U).
  double local_step();
  // B(U) from data.R (the rotations of the last local step), kept for plain_step and gradient.
  void assemble_rhs();
  // G = L_ff^{-1} B: the plain local/global iterate from the point assemble_rhs last saw (kept in this
  // object until the next call: the solve reuses its workspaces and allocates nothing).
  const Eigen::MatrixXd& plain_step();
  // g = L_ff x - B at the point assemble_rhs last saw (U's free rows must still hold it). Kept in this
  // object until the next call (no allocation per iteration).
  const Eigen::MatrixXd& gradient();
  // L_ff^{-1} r (r #free x 3).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const;

  // The Hessian of E(x) = min_R energy at the point of the last local step, for Newton-type steps:
  // prepare_hessian() keeps per cell M_c^{-1} = (tr(P_c) I - P_c)^{-1} with P_c = R_c^T S_c (what the
  // derivative of the polar rotation needs); hessian_product(v) then returns H v (v #free x 3).
  void prepare_hessian();
  Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v);

  // Back-substitutions with the factor so far (plain_step and solve).
  int solves() const { return solves_; }

private:
  ArapData& data_;
  Eigen::MatrixXd& U_;
  Eigen::MatrixXd Lfc_Uc_;                 // #free x 3
  Eigen::SparseMatrix<double> L_free_cols_; // #V x #free: columns `free` of the symmetric L (its free rows),
                                            // rows numbered in visit order
  ArapElements::ValueRows U_rows_;         // the positions in visit order (U's are written back at the end)
  Eigen::VectorXi free_row_;               // #free: the row of U_rows_ of free vertex data.free(i)
  std::vector<Eigen::Matrix3d> R_spare_;   // num_cells: where data.R goes back to the file's order
  Eigen::VectorXd cell_energy_;
  Eigen::MatrixXd rhs_, B_, X_, g_;
  std::vector<Eigen::Matrix3d> S_, M_inverse_, dR_; // Hessian workspaces (per cell)
  ArapElements::ValueRows v_rows_;                 // a direction v on all vertices, 0 at constrained ones
  Eigen::MatrixXd d_rhs_;
  mutable int solves_ = 0;
};

// sum_ij a_ij b_ij: the inner product of #free x 3 position-like matrices.
inline double inner(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.cwiseProduct(b).sum();
}

} // namespace iarap::detail
