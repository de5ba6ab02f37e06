// A resolved set of constraints: which vertices are fixed and where they must go, and the soft ones.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

// Soft constraints (and hard points on faces) as read from a file or scenario (the fields of the solver's
// ArapSoftConstraints, which this layer does not include): weighted vertices and points on faces with their
// targets. The penalty of point k is W_k ||c_k^T U - t_k||^2 (arap_soft_constraints.h).
struct SoftConstraintSet {
  Eigen::VectorXi vertices;       // #sv soft vertices, distinct, none of them also hard
  Eigen::VectorXd vertex_weights; // #sv W > 0
  Eigen::MatrixXd vertex_targets; // #sv x 3
  Eigen::VectorXi faces;          // #sb faces of the points
  Eigen::MatrixXd barycentric;    // #sb x 3, each row summing to 1 within 1e-9
  Eigen::VectorXd face_weights;   // #sb W > 0
  Eigen::MatrixXd face_targets;   // #sb x 3
  // Hard points on faces (c_k^T U = t_k exactly): 'b FACE B0 B1 B2 X Y Z' lines without a weight.
  Eigen::VectorXi hard_faces;       // #hb
  Eigen::MatrixXd hard_barycentric; // #hb x 3, each row summing to 1 within 1e-9
  Eigen::MatrixXd hard_targets;     // #hb x 3
  // #sv + #sb + #hb: where each came from (vertices first, then the soft and the hard face points), as
  // ConstraintSet::origins.
  std::vector<std::string> origins;
  Eigen::Index size() const { return vertices.size() + faces.size() + hard_faces.size(); }
};

// The input of arap_precompute / arap_solve: fixed(k) is a vertex index, targets.row(k) its position.
struct ConstraintSet {
  Eigen::VectorXi fixed;             // #C vertex indices, distinct
  Eigen::MatrixXd targets;           // #C x 3 target positions, finite
  std::vector<std::string> warnings; // e.g. identical duplicates that were merged
  // Empty, or #C entries: where constraint k came from ("file.txt:12", "scene.json: $.handles[0]"), so
  // that an error about a target can name the line or handle to fix.
  std::vector<std::string> origins;
  SoftConstraintSet soft; // empty for files and scenarios without weights
};

} // namespace iarap
