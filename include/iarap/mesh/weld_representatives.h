// Clusters of coincident vertices: which vertices repair_mesh welds and check_mesh reports as coincident.
#pragma once
#include <Eigen/Core>

namespace iarap {

// representative(i): the smallest vertex index in i's cluster, clusters being the connected groups of
// finite vertices of V (#V x 3) within `tolerance` (absolute, Euclidean) of each other; 0 joins identical
// positions only. Non-finite vertices stay alone. O(#V log #V) time and O(#V) memory whatever the
// coordinates (one outlier at 1e30, every vertex at one point), for tolerances down to 1e-13 of the
// extent of the vertices (check_mesh and repair_mesh use 1e-12 of the diagonal); below that, distinct
// vertices closer than 1e-13 of the extent are compared pairwise.
Eigen::VectorXi weld_representatives(const Eigen::MatrixXd& V, double tolerance);

} // namespace iarap
