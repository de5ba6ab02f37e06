// Deformation scenarios: fixed vertex sets and handles moved rigidly, resolved into constraints.
#pragma once
#include "iarap/scene/constraint_set.h"
#include "iarap/scene/region.h"

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace iarap {

// A set of vertices moved by one rigid motion: first the rotation about rotation_center, then the
// translation: target = R (v - c) + c + t.
struct Handle {
  std::string name;
  std::vector<Region> vertices;                             // union of the regions
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();    // absolute, or a multiple of the bbox diagonal
  bool translation_relative = false;                        // true: translation is in bbox diagonals
  Eigen::Vector3d rotation_axis = Eigen::Vector3d::UnitZ(); // any non-zero length when angle != 0
  double rotation_degrees = 0;
  // Centre of rotation; absent: the centroid of the handle's rest positions. When
  // rotation_center_relative, it is in bounding-box coordinates (see Region::relative).
  std::optional<Eigen::Vector3d> rotation_center;
  bool rotation_center_relative = false;
  // 0: hard targets. > 0: soft, penalty weight * |x_i - target_i|^2 per vertex (arap_soft_constraints.h):
  // "weight": W in a scenario's handle.
  double weight = 0;
  std::string path = "handle"; // named in error messages
};

struct Scenario {
  std::string description;
  std::vector<Region> fixed;         // union of the regions, kept at rest
  std::vector<Handle> handles;       // moved
  std::string source = "<scenario>"; // file it came from, named in error messages
};

// Resolves the scenario on the rest mesh V (#V x 3): fixed vertices first (targets = rest
// positions), then each hard handle's vertices in index order; soft handles' vertices (weight > 0) go to
// ConstraintSet::soft in the same order. Throws InputError naming the source and
// the region path when a region is invalid or empty, when a vertex is both fixed and in a handle or
// in two handles, when a rotation axis is zero, and when nothing is constrained.
ConstraintSet resolve_scenario(const Scenario& scenario, const Eigen::MatrixXd& V);

} // namespace iarap
