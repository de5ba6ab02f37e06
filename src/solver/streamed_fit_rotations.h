// The local step over the streamed layout (streamed_layout.h), with positions and rotations in the visit
// order: what the iterations call, and the covariance pass alone that `iarap bench` times. Internal to the
// solver; fit_rotations (fit_rotations.h) wraps it for callers in the file's order.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// fit_rotations in visit order: U_rows (#V x 3) holds the position of vertex visit_order[p] in row p, R[p]
// belongs to cell visit_order[p]. cell_energy stays in cell order, so that E(U) is the same sum, bit for
// bit. One sweep over the cell entries; OpenMP-parallel over cells, without atomics. When R holds
// num_cells rotations on entry they start each fit (polar_rotation_near). When covariances is given, it gets
// S_c too (num_cells, visit order).
double fit_rotations_in_visit_order(const ArapElements& elements, const ArapElements::ValueRows& U_rows,
                                    std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy,
                                    std::vector<Eigen::Matrix3d>* covariances = nullptr);

// The cells' energies (cell order, as fit_rotations_in_visit_order) for given rotations R (visit order)
// instead of fitted ones: the local step of a coupled fit (rotation_smoothing.h). Returns their sum.
double cell_energies_in_visit_order(const ArapElements& elements, const ArapElements::ValueRows& U_rows,
                                    const std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy);

// U_rows (#V x 3, row-major) = U's rows in visit order: row p is U's row visit_order[p].
void visit_rows(const ArapElements& elements, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows);

// The covariances S_c of fit_rotations alone, in visit order (S[p] for cell visit_order[p], num_cells),
// from positions U_rows in visit order (visit_rows), in the same sweep: the memory-bound floor of the local
// step that `iarap bench` reports (element_pass_ms).
void cell_covariances(const ArapElements& elements, const ArapElements::ValueRows& U_rows,
                      std::vector<Eigen::Matrix3d>& S);

} // namespace iarap::detail
