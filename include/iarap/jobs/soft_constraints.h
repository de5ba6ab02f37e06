// The solver's soft constraints (ArapSoftConstraints) from those a constraints file or scenario gives
// (SoftConstraintSet), their targets in the solver's order (vertices first, then the soft face points, then
// the hard ones), and a HardPointConflict told with the lines the points came from: the bridge between the
// scene layer and the solver that every job (deform, simulate, the server's session) crosses.
#pragma once
#include "iarap/scene/constraint_set.h"
#include "iarap/solver/arap_soft_constraints.h"

#include <Eigen/Core>

#include <string>

namespace iarap {

inline ArapSoftConstraints soft_constraints_of(const SoftConstraintSet& set) {
  ArapSoftConstraints soft;
  soft.vertices = set.vertices;
  soft.vertex_weights = set.vertex_weights;
  soft.faces = set.faces;
  soft.barycentric = set.barycentric;
  soft.face_weights = set.face_weights;
  soft.hard_faces = set.hard_faces;
  soft.hard_barycentric = set.hard_barycentric;
  return soft;
}

inline Eigen::MatrixXd soft_targets_of(const SoftConstraintSet& set) {
  Eigen::MatrixXd T(set.size(), 3);
  if (set.vertices.size() > 0) T.topRows(set.vertices.size()) = set.vertex_targets;
  if (set.faces.size() > 0) T.middleRows(set.vertices.size(), set.faces.size()) = set.face_targets;
  if (set.hard_faces.size() > 0) T.bottomRows(set.hard_faces.size()) = set.hard_targets;
  return T;
}

// The solver's HardPointConflict told with the file lines (or scenario paths) of the two points.
inline std::string hard_point_conflict_message(const HardPointConflict& e, const SoftConstraintSet& set) {
  const Eigen::Index first = set.vertices.size() + set.faces.size();
  const auto origin = [&](Eigen::Index k) {
    const auto at = static_cast<size_t>(first + k);
    return at < set.origins.size() ? set.origins[at] : "hard face point " + std::to_string(k);
  };
  if (e.other < 0)
    return origin(e.point) +
           ": this hard point on a face contradicts the fixed vertices: its corners are all fixed (or it "
           "repeats fixed vertices) and its target is not where they put it";
  return origin(e.point) + ": this hard point on a face contradicts the one at " + origin(e.other) +
         " (with the fixed vertices): the same point, or a combination of points already held, is asked "
         "to go to a different target";
}

} // namespace iarap
