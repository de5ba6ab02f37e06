// The local step shared by the three ARAP energies: optimal cell rotations and the energy they attain.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>
#include <vector>

namespace iarap {

// For deformed positions U (#V x 3): the cell covariances S_c = sum_{e in c} w_e s_e s_hat_e^T with
// s_e = U^T b_e (Eq. 15), the rotations R_c maximizing tr(R_c^T S_c) (polar_rotation; elements.num_cells,
// written to R) and the cell energies E_c = sum_{e in c} (w_e / 2) ||s_e - R_c s_hat_e||^2
// (elements.num_cells, written to cell_energy; cells 0..#V-1 are the vertices). Returns E(U) = sum_c E_c,
// the variant's energy minimized over the rotations (summed in cell order, so the value does not depend
// on the thread count). When R holds elements.num_cells rotations on entry (the previous iterate's), they
// start each fit (polar_rotation_near: the same rotations, fewer steps); otherwise each fit starts cold.
// U_rows is a workspace (U's rows in visit order: visit_rows) reused between calls. U must be #V x 3 with
// #V = elements.num_vertices (not checked: hot path). The arrays are in the file's order; the iterations
// keep theirs in visit order and call fit_rotations_in_visit_order, which this wraps.
double fit_rotations(const ArapElements& elements, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows,
                     std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy);

// fit_rotations with the positions and rotations in visit order (ArapElements::visit_order): U_rows
// (#V x 3) holds the position of vertex visit_order[p] in row p, R[p] belongs to cell visit_order[p].
// cell_energy stays in cell order, so that E(U) is the same sum, bit for bit. One sweep over
// elements.cell_entry; OpenMP-parallel over cells, without atomics.
// When covariances is given, it gets S_c too (num_cells, visit order).
double fit_rotations_in_visit_order(const ArapElements& elements, const ArapElements::ValueRows& U_rows,
                                    std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy,
                                    std::vector<Eigen::Matrix3d>* covariances = nullptr);

// U_rows (#V x 3, row-major) = U's rows in visit order: row p is U's row elements.visit_order[p].
void visit_rows(const ArapElements& elements, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows);

// The covariances S_c of fit_rotations alone, in visit order (S[p] for cell visit_order[p], num_cells),
// from positions U_rows in visit order (visit_rows), in the same sweep: the memory-bound floor of the local
// step that `iarap bench` reports (element_pass_ms).
void cell_covariances(const ArapElements& elements, const ArapElements::ValueRows& U_rows,
                      std::vector<Eigen::Matrix3d>& S);

} // namespace iarap
