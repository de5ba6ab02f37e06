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
// U_rows is a workspace reused between calls. U must be #V x 3 with #V = elements.num_vertices (not
// checked: hot path). All arrays are in the file's order.
double fit_rotations(const ArapElements& elements, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows,
                     std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy);

} // namespace iarap
