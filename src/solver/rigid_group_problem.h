// The local/global problem with rigid groups (iarap/solver/rigid_groups.h): the unknowns y are the free
// vertices in no group and the translations of the Free groups; U = P y + U_R(R_g) places the groups by
// their rotations R_g, which the local step fits (with the cell rotations) like the cells'. Energy, right-
// hand side and gradient are of the same total as LocalGlobalProblem's (the quadratic terms' soft points and
// forces included): E(U) = min_R sum_c E_c + sum_t E_t, B = P^T (b(R) - A U_R), g = P^T (A U - b(R)) with
// A = L + Q and b = rhs(R) + sum_t s_t, the plain step y = K^{-1} B, K = P^T A P.
//
// The local step runs three block minimizations in turn, each exact over its block: the group rotations
// R_g one group after another (with the cell rotations of the last local step and everything else fixed,
// E = const - tr(R_g^T M_g), M_g = -sum_{i in g} (A U - b)_i q_i^T + R_g K_g with K_g =
// sum_{i,j in g} A_ij q_j q_i^T, q_i = p_i - o_g: its best rotation is polar(M_g)), then the cell
// rotations; the global step then minimizes over y. So the energy never increases from iterate to iterate.
// The group rotations are state of the problem beside y: only the plain iteration runs on it (arap_solve
// refuses the accelerators), and it has no Hessian. Everything is in the file's order. Internal.
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

  Eigen::Index free_count() const override { return y_.rows(); }
  Eigen::Index dimension() const override { return 3; }
  Eigen::MatrixXd positions() const override { return y_; }
  void set_positions(const Eigen::MatrixXd& y) override;

  // The group rotations (once a right-hand side has been assembled), then the cell rotations; returns the
  // total energy at the resulting U.
  double local_step() override;
  void assemble_rhs() override;
  const Eigen::MatrixXd& plain_step() override;
  const Eigen::MatrixXd& gradient() const override { return g_; }
  Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const override;

  // Not available (the rigid map is nonlinear in R_g): SolverError.
  void prepare_hessian() override;
  Eigen::MatrixXd hessian_product(const Eigen::MatrixXd& v) override;

  int solves() const override { return solves_; }

private:
  void fit_group_rotations();
  void place_groups(); // U's rows from y, R_g and t_g

  ArapData& data_;
  Eigen::MatrixXd& U_;
  Eigen::SparseMatrix<double> A_; // L + Q
  std::vector<std::unique_ptr<QuadraticTerm>> terms_;
  Eigen::MatrixXd s_;                      // #V x 3: sum_t s_t
  Eigen::MatrixXd q_;                      // #V x 3: p_i - o_g of group members (0 elsewhere)
  std::vector<Eigen::Matrix3d> R_g_, K_g_; // per group
  std::vector<Eigen::Vector3d> t_g_;       // per group (Free: y's row, kept in step)
  Eigen::MatrixXd y_, B_, g_, X_, b_;      // b_ = rhs(R) + s of the last assemble_rhs
  bool have_b_ = false;                    // assemble_rhs ran since the cell rotations changed
  ArapElements::ValueRows U_rows_;         // fit_rotations' workspace
  ArapElements::ValueRows term_rows_;      // U for the quadratic terms
  Eigen::VectorXd cell_energy_;
  mutable int solves_ = 0;
};

} // namespace iarap::detail
