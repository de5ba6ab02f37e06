// The system of the rigid groups (iarap/solver/rigid_groups.h) as arap_precompute builds it, and the rigid
// fits the solve starts from. Internal to the solver.
#pragma once
#include "iarap/solver/arap_types.h"

#include "constraint_layout.h"

#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// The system of `groups` on data's mesh (data.V, data.L, data.planar) with the soft constraints' Q and soft
// (data's may not be set yet) for the constrained set fixed (#fixed) laid out by layout (its pinned
// vertices and free slots). Throws InputError for bad groups (check_rigid_groups), hard points on faces (not
// supported with groups) and a group whose two or more constrained vertices cannot determine its rotation
// (all on one line; planar: all at one point); SolverError when K cannot be factorized.
RigidGroupSystem rigid_group_system(const std::vector<std::vector<int>>& groups, const ArapData& data,
                                    const Eigen::SparseMatrix<double>& Q, const ArapSoftConstraints& soft,
                                    const Eigen::VectorXi& fixed, const ConstraintLayout& layout);

// The rotation R (about z when planar) maximizing sum_k (R q_k) . x_k = tr(R^T sum_k x_k q_k^T): the best
// rotation of the rest offsets q (rows) onto the moved offsets x (rows); both about their centroids, it is
// the rotation of the least-squares rigid fit (Kabsch), whose translation maps one centroid onto the other.
Eigen::Matrix3d best_rotation(const Eigen::MatrixXd& q, const Eigen::MatrixXd& x, bool planar);

} // namespace iarap::detail
