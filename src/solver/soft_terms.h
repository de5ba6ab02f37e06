// The soft constraints (arap_soft_constraints.h) as the solver uses them: checked, one point per soft
// vertex or face point with its three corners, their matrix Q = sum_k 2 W_k c_k c_k^T and the penalty
// P(U) = sum_k W_k ||c_k^T U - t_k||^2. Internal to the solver.
#pragma once
#include "iarap/solver/arap_soft_constraints.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace iarap::detail {

// One soft point: c^T U = sum_j c[j] U.row(v[j]). A soft vertex i is v = (i, i, i), c = (1, 0, 0). A hard
// point is one too, with W = kHardPointWeight (its internal term in Q).
struct SoftPoint {
  int v[3];
  double c[3];
  double W;
};

// Throws InputError naming the entry: lengths that differ, a vertex out of range (of n) or also in
// `fixed`, a face out of range of F, a weight that is not finite and > 0, barycentric coordinates that are
// not finite or do not sum to 1 within 1e-9; the same for the hard points.
void check_soft_constraints(const ArapSoftConstraints& soft, int n, const Eigen::MatrixXi& F,
                            const Eigen::VectorXi& fixed);

// The points of soft (vertices first, then face points, then the hard points), in the order of the soft
// targets.
std::vector<SoftPoint> soft_points(const ArapSoftConstraints& soft, const Eigen::MatrixXi& F);

// Q (n x n) = sum_k 2 W_k c_k c_k^T; 0 x 0 when there is no point (so that L + Q is not formed at all).
Eigen::SparseMatrix<double> soft_system_matrix(const std::vector<SoftPoint>& points, int n);

// L + Q, or L itself (bit for bit) when Q is 0 x 0.
Eigen::SparseMatrix<double> with_soft(const Eigen::SparseMatrix<double>& L,
                                      const Eigen::SparseMatrix<double>& Q);

// P(U) over the first `count` points (the soft ones: ArapSoftConstraints::soft_size) for targets
// #points x 3 and U #V x 3 (rows indexed by row_of[v] when row_of is given).
double soft_penalty(const std::vector<SoftPoint>& points, const Eigen::MatrixXd& targets, const double* U,
                    const std::vector<int>* row_of, size_t count);

} // namespace iarap::detail
