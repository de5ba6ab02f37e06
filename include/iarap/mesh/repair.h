// Opt-in repair of the defects check_mesh warns about: unwelded copies of a vertex, unreferenced vertices,
// zero-area faces. Vertex order is kept for the vertices that stay.
#pragma once
#include "iarap/mesh/weld_representatives.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

struct RepairOptions {
  bool weld = true;              // merge vertices closer than weld_tolerance * bbox diagonal
  double weld_tolerance = 1e-12; // relative to the bounding-box diagonal; 0 merges identical positions only
  bool remove_unreferenced = true;
  bool remove_zero_area = false; // faces with area <= 1e-12 * bbox_diagonal^2
};

struct RepairResult {
  Eigen::MatrixXd V;          // #V_new x 3
  Eigen::MatrixXi F;          // #F_new x 3
  Eigen::VectorXi old_to_new; // #V_old: new index of each old vertex (its weld target's), -1 where removed
  std::vector<std::string> actions; // one line per change made, with counts
};

// Welding keeps the smallest index of each cluster; faces that welding collapses (a repeated vertex) are
// removed. Throws InputError when V is not #V x 3, F not #F x 3, or a face index is out of range.
RepairResult repair_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                         const RepairOptions& options = {});

} // namespace iarap
