// Hard point constraints C x = d on the global step's unknowns x (#free x 3; arap_soft_constraints.h),
// eliminated on the factorized A = (L + Q)_ff by the Schur complement of the KKT system
//
//   [A  C^T] [x     ]   [b]
//   [C  0  ] [lambda] = [d]:   x = A^{-1} b - Y S^{-1} (C A^{-1} b - d),   Y = A^{-1} C^T,  S = C Y.
//
// Y costs one solve with a column per point, S is #points x #points: meant for up to a few hundred points.
// Internal to the solver.
#pragma once
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <functional>
#include <optional>
#include <vector>

namespace iarap::detail {

// One row of C: c^T x = sum_j c[j] x.row(column[j]) over the corners that are unknowns (column -1: a
// corner that is not, whose share went into d).
struct ConstraintRow {
  int column[3];
  double c[3];
};

// A row of C that is a combination of earlier rows (row = sum_i alpha_i row_i) while its d is not the same
// combination of theirs: the two cannot hold together.
struct ConstraintConflict {
  Eigen::Index row;
  Eigen::Index depends_on; // the earlier row with the largest |alpha_i|, -1 for a zero row
  double gap;              // ||d_row - sum_i alpha_i d_i||
};

class HardPointProjection {
public:
  HardPointProjection() = default;
  // rows: C (#rows x n); solve(B) returns A^{-1} B for an n x k B (A symmetric, non-singular). Rows are
  // kept greedily in order while independent (Gram matrix C C^T, relative pivot above 1e-12); the others
  // are checked by find_conflict and otherwise ignored.
  HardPointProjection(std::vector<ConstraintRow> rows, Eigen::Index n,
                      const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& solve);

  bool empty() const { return rows_.empty(); }
  // x -= Y S^{-1} (C x - d) over the independent rows: the point on C x = d closest to x in A's norm. With
  // x = A^{-1} b it is the constrained minimizer of x^T A x / 2 - b^T x. d: #rows x 3.
  void correct(Eigen::MatrixXd& x, const Eigen::MatrixXd& d) const;
  // The same with d = 0: A^{-1}-preconditioned directions onto the constraints' tangent space.
  void project(Eigen::MatrixXd& x) const;
  // g -= C^T S^{-1} Y^T g, so that A^{-1} g becomes project(A^{-1} g): the gradient whose preconditioned
  // step keeps C x = d, zero at the constrained minimizer.
  void project_gradient(Eigen::MatrixXd& g) const;
  // The first dependent row whose d is off the combination of the independent rows' by more than tol.
  std::optional<ConstraintConflict> find_conflict(const Eigen::MatrixXd& d, double tol) const;

private:
  Eigen::MatrixXd independent_times(const Eigen::MatrixXd& x) const; // C_I x

  std::vector<ConstraintRow> rows_;
  std::vector<Eigen::Index> independent_;                           // I, increasing
  std::vector<std::pair<Eigen::Index, Eigen::VectorXd>> dependent_; // row and its alpha over I
  Eigen::MatrixXd Y_;                                               // n x |I|
  // C_I Y (LDLT: A may be indefinite); none without independent rows. Optional, not an empty LDLT: Eigen's
  // leaves its status unset until compute(), and copying it would read that (UBSan: an invalid enum).
  std::optional<Eigen::LDLT<Eigen::MatrixXd>> S_;
};

} // namespace iarap::detail
