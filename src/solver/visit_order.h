// The order in which the iterations visit the rotation cells and the vertices: a breadth-first order of the
// mesh, so that cells visited one after the other read the same positions and rotations while they are
// still in cache. Internal to the solver; nothing outside the iteration arrays sees it (ArapElements).
#pragma once
#include "iarap/solver/arap_elements.h"

#include <vector>

namespace iarap::detail {

// A permutation of the num_cells cells (position -> cell): the #V vertex cells first, in breadth-first
// order over "cell c reads vertex v" (v in b_e for an element e of c) from an extreme vertex of the rest
// mesh V (#V x 3), each further connected piece from its first vertex; then the inserted boundary cells
// (iARAP with refine_boundary) in their own order. Needs cell_element_start / cell_element and b_index.
//
// Why: a file's vertex order is often far from local (1-to-4 subdivision numbers each edge's midpoint after
// all the corners; scanned or shuffled meshes worse), and the local step's gathers and the right-hand
// side's then miss the cache once the positions and rotations outgrow it. This is the Cuthill-McKee order
// without its per-level sort by degree, which matters for a band's width, not for a cache; it is written
// here because the libraries the project uses offer none (Boost.Graph has one; CHOLMOD's AMD and METIS
// orders reduce fill and are no locality order).
std::vector<int> breadth_first_cell_order(const ArapElements& el, const Eigen::MatrixXd& V);

// The inverse of el.visit_order (num_cells): position[c] = p where visit_order[p] = c.
std::vector<int> visit_positions(const ArapElements& el);

// Per-cell rotations between the file's cell order and el.visit_order (num_cells each; out is resized):
// to: out[p] = R[visit_order[p]]; from: out[visit_order[p]] = R[p].
void rotations_to_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R,
                              std::vector<Eigen::Matrix3d>& out);
void rotations_from_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R,
                                std::vector<Eigen::Matrix3d>& out);

} // namespace iarap::detail
