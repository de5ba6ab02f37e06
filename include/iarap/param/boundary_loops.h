// The boundary loops of a triangle mesh: the closed chains of edges that have one face.
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap {

// Each loop lists its vertices in the direction the faces traverse their boundary edges (for a disk whose
// faces are counter-clockwise seen from above, counter-clockwise around the disk), starting at the loop's
// smallest vertex index; loops are ordered by that vertex. F is #F x 3 with indices in
// 0..num_vertices-1, consistently oriented. A closed mesh has no loop. Throws TopologyError naming the
// vertex where two boundary edges leave one vertex (a non-manifold vertex, or faces of opposite
// orientation) or where a chain does not close. O(#F log(valence) + #V).
std::vector<std::vector<int>> boundary_loops(const Eigen::MatrixXi& F, int num_vertices);

} // namespace iarap
