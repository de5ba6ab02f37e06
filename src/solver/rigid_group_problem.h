// The local/global problem with rigid groups (iarap/solver/rigid_groups.h) in reduced coordinates: each
// group is one rigid body. The unknowns x = [y; w] are y (the free vertices in no group and the translations
// t_g of the Free groups, the rows of the global step's K = P^T A P) and w, one rotation vector per Free or
// Pivot group (rotation_vector.h): R_g = exp([w_g]x) R_0g about the group's fit to the initial guess R_0g
// (Held groups are fixed by their targets). The members sit at U_i = R_g q_i + t_g, q_i = p_i - o_g, so
// U = P y + U_R(w). E(x) = min_R sum_c E_c(U(x)) + sum_t E_t(U(x)) is a function of x alone (the local step
// fits the cell rotations only), which every accelerator can minimize. With A = L + Q, b = rhs(R) + sum_t
// s_t and G = A U - b (dE/dU by the envelope theorem):
//   gradient  g_y = P^T G,  g_w = J(w_g)^T tau_g,  tau_g = sum_{i in g} r_i x G_i  (r_i = R_g q_i, the
//   torque); Hessian   H = T^T H_U T + [J^T N_g J + sym(dJ^T tau_g / dw)] on each group's w block, with T the
//   map
//             (v_y, v_w) -> P v_y + (J v_w) x r_i, H_U v = A v - rhs(dR[v]) the Hessian of min_R E in U (as
//             LocalGlobalProblem's) and N_g = sum_i sym(G_i r_i^T) - (r_i . G_i) I the second-order change
//             of a turned member's position (r + d x r + d x (d x r) / 2);
//   plain step, from the point of the last assemble_rhs: the group rotations refitted one group after
//             another (with the cell rotations of the last local step and everything else fixed,
//             E = const - tr(R_g^T M_g), M_g = -sum_{i in g} G_i q_i^T + R_g K_g, K_g = sum_{i,j in g}
//             A_ij q_j q_i^T: R_g = polar(M_g)), then y = K^{-1} P^T (b - A U_R): each block step is
//             exact, so it never raises the energy.
//   preconditioner: the quadratic form of A in x at the current turns, [K C; C^T D] = T^T A T (the global
//             step's matrix with the turns as unknowns too: L_ff's role without groups), applied through
//             its Schur complement S = D - C^T K^{-1} C (3 per turning group square, dense): Z = K^{-1} C
//             takes 3 back-substitutions per turning group each time the turns change.
// The rotation vectors stay principal (|w| <= pi) as the plain step takes them; J is invertible below 2 pi.
// Everything is in the file's order. Internal.
#pragma once
#include "iarap/solver/arap_types.h"

#include "problem.h"
#include "quadratic_terms.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace iarap::detail {

class RigidGroupProblem final : public Problem {
public:
  // Sets U's constrained rows (targets at data.fixed, U's own rows at data.pinned), fits each group to the
  // initial guess (Free: the rigid fit of its members' guesses; Pivot: the rotation about its constrained
  // member; Held: the rigid fit of its constrained members' targets, InputError naming the group when they
  // are off a rigid motion by more than 1e-9 of the diagonal) and moves U onto the rigid groups. data and U
  // must outlive the problem. soft_targets and forces as for LocalGlobalProblem (no hard points).
  RigidGroupProblem(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                    const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& forces);

  Eigen::Index free_count() const override { return y_.rows() + w_.rows(); }
  Eigen::Index dimension() const override { return 3; }
  Eigen::MatrixXd positions() const override; // [y; w]
  void set_positions(const Eigen::MatrixXd& x) override;

  // The cell rotations at U(x); returns the total energy there.
  double local_step() override;
  void assemble_rhs() override;
  const Eigen::MatrixXd& plain_step() override;
  const Eigen::MatrixXd& gradient() const override { return g_; }
  // The preconditioner above: [K C; C^T D]^{-1} r.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const override;

  void prepare_hessian() override;
  Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v) override;

  int solves() const override { return solves_; }

private:
  void place_groups(); // R_g and J from w, U's rows from y, R_g and t_g
  // The positions' change (J_k e) x r_i of the members of turning group k (row k of w), 0 elsewhere.
  Eigen::MatrixXd turn_field(size_t k, const Eigen::Vector3d& e) const;
  void prepare_preconditioner() const; // Z_ and the Schur complement's inverse at the current turns
  // (A U - b) at row i (A symmetric: its column i).
  Eigen::RowVector3d residual_row(const Eigen::MatrixXd& U, int i) const;
  // The positions' change T v for v = [v_y; v_w] (zero at constrained rows), and each group's turn J v_w.
  Eigen::MatrixXd position_change(const Eigen::MatrixXd& v, std::vector<Eigen::Vector3d>& turn) const;

  ArapData& data_;
  Eigen::MatrixXd& U_;
  Eigen::SparseMatrix<double> A_; // L + Q
  std::vector<std::unique_ptr<QuadraticTerm>> terms_;
  Eigen::MatrixXd s_;                           // #V x 3: sum_t s_t
  Eigen::MatrixXd q_;                           // #V x 3: p_i - o_g of group members (0 elsewhere)
  std::vector<Eigen::Matrix3d> R0_, R_g_, K_g_; // per group
  std::vector<Eigen::Vector3d> t_g_;            // per group (Free: y's row)
  std::vector<int> rotation_row_;               // per group: its row of w (Free, Pivot), -1 (Held)
  std::vector<int> turning_;                    // the groups with a row of w, in row order
  Eigen::MatrixXd y_, w_;                       // the unknowns
  std::vector<Eigen::Matrix3d> J_;              // per row of w: J(w_g)
  std::vector<int> axes_;                       // the turns' axes: x y z, planar z only
  mutable std::vector<Eigen::MatrixXd> Z_;      // per (row of w, axis): K^{-1} C's column
  mutable Eigen::MatrixXd schur_inverse_;       // S^+ over (row of w, axis)
  mutable bool preconditioner_stale_ = true;
  std::vector<Eigen::Matrix3d> turn_hessian_; // per row of w: J^T N_g J + sym(dJ^T tau / dw)
  Eigen::MatrixXd b_, G_, g_, X_;             // at the point of the last assemble_rhs
  Eigen::MatrixXd U_b_, y_b_;                 // that point's U and y
  std::vector<Eigen::Matrix3d> R_b_;          // its group rotations
  std::vector<Eigen::Vector3d> t_b_;          // its translations
  std::vector<Eigen::Vector3d> torque_;       // per row of w, there
  ArapElements::ValueRows U_rows_;            // fit_rotations' workspace
  ArapElements::ValueRows term_rows_;         // U for the quadratic terms
  Eigen::VectorXd cell_energy_;
  std::vector<Eigen::Matrix3d> M_inverse_, dR_; // per cell: (tr(P_c) I - P_c)^{-1}, P_c = R_c^T S_c; dR_c
  mutable int solves_ = 0;
};

} // namespace iarap::detail
