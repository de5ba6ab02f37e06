#include "rigid_groups.h"

#include "iarap/core/errors.h"
#include "iarap/solver/polar_rotation.h"

#include "soft_terms.h"

#include <Eigen/SVD>

#include <string>

namespace iarap {

void check_rigid_groups(const std::vector<std::vector<int>>& groups, Eigen::Index n) {
  std::vector<int> group_of(static_cast<size_t>(n), -1);
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string name = "ARAP: rigid group " + std::to_string(g);
    if (groups[g].size() < 2)
      throw InputError(name + " has " + std::to_string(groups[g].size()) +
                       " vertices; a rigid group needs at least 2");
    for (const int v : groups[g]) {
      if (v < 0 || v >= n)
        throw InputError(name + " names vertex " + std::to_string(v) + ", out of range for a mesh of " +
                         std::to_string(n) + " vertices");
      int& first = group_of[static_cast<size_t>(v)];
      if (first == static_cast<int>(g))
        throw InputError(name + " names vertex " + std::to_string(v) + " twice");
      if (first >= 0)
        throw InputError(name + " names vertex " + std::to_string(v) + ", already in rigid group " +
                         std::to_string(first));
      first = static_cast<int>(g);
    }
  }
}

namespace detail {

namespace {

// The rows of V at `rows`, less their centroid.
Eigen::MatrixXd centered_rows(const Eigen::MatrixXd& V, const std::vector<int>& rows) {
  Eigen::MatrixXd X(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t k = 0; k < rows.size(); ++k) X.row(static_cast<Eigen::Index>(k)) = V.row(rows[k]);
  return X.rowwise() - X.colwise().mean();
}

// Two or more constrained members fix the group's rotation when their rest positions span a plane (3D) or
// a line (planar); anything less leaves a turn about them free, which the group has no energy to decide
// against its own rigidity (it would be a Pivot on a line): refused.
void check_held_members_determine_rotation(const Eigen::MatrixXd& V, const std::vector<int>& held,
                                           bool planar, size_t group) {
  const Eigen::MatrixXd X = centered_rows(V, held);
  const double extent = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  // min(#held, 3) singular values: two held members in space have two, the second zero (a line).
  const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(X).singularValues();
  const Eigen::Index needed = planar ? 0 : 1; // the singular value that must not vanish
  if (needed < sigma.size() && sigma(needed) > 1e-9 * extent) return;
  throw InputError("ARAP: rigid group " + std::to_string(group) + " has " + std::to_string(held.size()) +
                   " constrained vertices (e.g. " + std::to_string(held[0]) + ") " +
                   (planar ? "at one point" : "on one line") +
                   ": they do not determine its rotation; constrain at most one of its vertices (the group "
                   "turns about it) or " +
                   (planar ? "two apart" : "three not on a line"));
}

} // namespace

Eigen::Matrix3d best_rotation(const Eigen::MatrixXd& q, const Eigen::MatrixXd& x, bool planar) {
  const Eigen::Matrix3d S = x.transpose() * q; // sum_k x_k q_k^T
  return planar ? planar_rotation(S) : polar_rotation(S);
}

RigidGroupSystem rigid_group_system(const std::vector<std::vector<int>>& groups, const ArapData& data,
                                    const Eigen::SparseMatrix<double>& Q, const ArapSoftConstraints& soft,
                                    const Eigen::VectorXi& fixed, const ConstraintLayout& layout) {
  const Eigen::Index n = data.V.rows();
  check_rigid_groups(groups, n);
  if (soft.hard_faces.size() > 0)
    throw InputError("ARAP: rigid groups with hard points on faces are not supported; give the points as "
                     "soft points (a large weight) or constrain vertices");
  RigidGroupSystem system;
  system.groups = groups;
  system.group_of = Eigen::VectorXi::Constant(n, -1);
  std::vector<char> constrained(static_cast<size_t>(n), 0);
  for (Eigen::Index k = 0; k < fixed.size(); ++k) constrained[static_cast<size_t>(fixed(k))] = 1;
  for (const int v : layout.pinned) constrained[static_cast<size_t>(v)] = 1;
  system.kind.resize(groups.size());
  system.held.resize(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    for (const int v : groups[g]) {
      system.group_of(v) = static_cast<int>(g);
      if (constrained[static_cast<size_t>(v)]) system.held[g].push_back(v);
    }
    const size_t held = system.held[g].size();
    system.kind[g] = held == 0   ? RigidGroupKind::Free
                     : held == 1 ? RigidGroupKind::Pivot
                                 : RigidGroupKind::Held;
    if (held >= 2) check_held_members_determine_rotation(data.V, system.held[g], data.planar, g);
  }
  // y = [free vertices in no group; Free groups' translations].
  system.unknown_of = Eigen::VectorXi::Constant(n, -1);
  system.group_unknown = Eigen::VectorXi::Constant(static_cast<Eigen::Index>(groups.size()), -1);
  int rows = 0;
  for (Eigen::Index v = 0; v < n; ++v)
    if (layout.free_slot(v) >= 0 && system.group_of(v) < 0) system.unknown_of(v) = rows++;
  for (size_t g = 0; g < groups.size(); ++g)
    if (system.kind[g] == RigidGroupKind::Free) system.group_unknown(static_cast<Eigen::Index>(g)) = rows++;
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index v = 0; v < n; ++v) {
    const int g = system.group_of(v);
    const int column = g >= 0 ? system.group_unknown(g) : system.unknown_of(v);
    if (column >= 0) entries.emplace_back(static_cast<int>(v), column, 1.0);
  }
  system.P.resize(n, rows);
  system.P.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> A = with_soft(data.L, Q);
  const Eigen::SparseMatrix<double> K = system.P.transpose() * A * system.P;
  try {
    system.solver.factorize(K);
  } catch (const SolverError& e) {
    throw SolverError(std::string("ARAP: the global step's system with rigid groups cannot be factorized: ") +
                      e.what());
  }
  return system;
}

} // namespace detail

} // namespace iarap
