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
};

} // namespace iarap
