// The solver's soft constraints from those a constraints file or scenario gives (ConstraintSet::soft), and
// their targets in the solver's order (vertices first, then the face points): shared by deform and simulate.
#pragma once
#include "iarap/scene/constraint_set.h"
#include "iarap/solver/arap_soft_constraints.h"

#include <Eigen/Core>

namespace iarap::cli {

inline ArapSoftConstraints soft_constraints_of(const SoftConstraintSet& set) {
  ArapSoftConstraints soft;
  soft.vertices = set.vertices;
  soft.vertex_weights = set.vertex_weights;
  soft.faces = set.faces;
  soft.barycentric = set.barycentric;
  soft.face_weights = set.face_weights;
  return soft;
}

inline Eigen::MatrixXd soft_targets_of(const SoftConstraintSet& set) {
  Eigen::MatrixXd T(set.size(), 3);
  if (set.vertices.size() > 0) T.topRows(set.vertices.size()) = set.vertex_targets;
  if (set.faces.size() > 0) T.bottomRows(set.faces.size()) = set.face_targets;
  return T;
}

} // namespace iarap::cli
