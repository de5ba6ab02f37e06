// Rigid parts (issue 45): groups of vertices that move as one rigid body, x_i = R_g (p_i - o_g) + t_g for
// every member i of group g (p the rest positions). ArapOptions::rigid_groups names them; arap_precompute
// builds the system below and arap_solve keeps every group exactly rigid.
//
// The energy is the variant's own, E(U) = min_R sum_c E_c(U, R_c) (every cell keeps its own rotation, as
// a hard-constrained vertex's does), minimized over the positions that keep the groups rigid. With the
// rotations fixed the energy is quadratic in U with Hessian L (+ Q), and a group's positions are
// affine in (free unknowns, t_g) once R_g is fixed: U = P y + U_R(R), so the global step solves
// K y = P^T (b(R) - L U_R(R)) with K = P^T L P, constant and factorized once. The plain step fits R_g
// exactly (the energy is -tr(R_g^T M_g) + const in R_g: R_g q . R_g q = q . q), group after group, then
// solves for y; the local step fits the cell rotations: each block step minimizes over its block, so the
// energy never increases. The accelerators see each group as one rigid body, its translation (Free) and a
// rotation vector (rigid_group_problem.h: the energy, gradient and Hessian of those unknowns alone).
//
// A group's kind follows from its hard-constrained (fixed or pinned) members:
//   none:            Free, o_g = the members' rest centroid, t_g an unknown of the global step;
//   one, vertex k:   Pivot, o_g = p_k and t_g = its target: the group turns about it;
//   two or more:     Held, R_g and t_g are the rigid fit (Kabsch) of their targets, which must be a rigid
//                    motion of their rest positions to 1e-9 of the mesh's diagonal (InputError otherwise),
//                    and must determine the rotation (not all on one line in 3D; planar: not coincident).
#pragma once
#include "iarap/solver/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace iarap {

enum class RigidGroupKind { Free, Pivot, Held };

// What arap_precompute builds from ArapOptions::rigid_groups for the constrained set (empty: no groups).
struct RigidGroupSystem {
  std::vector<std::vector<int>> groups; // the members of each group, as given
  std::vector<RigidGroupKind> kind;     // per group
  std::vector<std::vector<int>> held;   // per group: its constrained members
  Eigen::VectorXi group_of;             // #V: the group of each vertex, -1 for none
  // The unknowns y of the global step (#y x 3): the free vertices in no group, then one translation per Free
  // group. unknown_of: #V row of y of a free vertex in no group, -1 otherwise; group_unknown: per group
  // its row of y (Free), -1 otherwise.
  Eigen::VectorXi unknown_of, group_unknown;
  Eigen::SparseMatrix<double> P; // #V x #y: the members of a Free group share their translation's column
  SparseCholesky solver;         // K = P^T (L + Q) P
  bool empty() const { return groups.empty(); }
};

// Throws InputError naming the group (0-based, in the order given) for a vertex index out of 0..n-1, a
// group of fewer than 2 vertices, a vertex named twice in a group or in two groups.
void check_rigid_groups(const std::vector<std::vector<int>>& groups, Eigen::Index n);

} // namespace iarap
