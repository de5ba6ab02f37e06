// A resolved set of hard constraints: which vertices are fixed and where they must go.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

// The input of arap_precompute / arap_solve: fixed(k) is a vertex index, targets.row(k) its position.
struct ConstraintSet {
  Eigen::VectorXi fixed;             // #C vertex indices, distinct
  Eigen::MatrixXd targets;           // #C x 3 target positions, finite
  std::vector<std::string> warnings; // e.g. identical duplicates that were merged
  // Empty, or #C entries: where constraint k came from ("file.txt:12", "scene.json: $.handles[0]"), so
  // that an error about a target can name the line or handle to fix.
  std::vector<std::string> origins;
};

} // namespace iarap
