// Right-hand side of the ARAP global step (paper Eq. 16), gathered per vertex.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>
#include <vector>

namespace iarap {

// rhs (#V x 3) with row v = sum_e w_e (b_e)_v ((sum_{c in cells(e)} R_c) s_hat_e)^T (Eq. 16; the paper's
// (R_i + R_j) / 2 times the 2 cells of L = 2 B^T D_w B), evaluated as sum_c R_c p_vc over the vertex's
// (cell, p_vc) terms regrouped once by the element builders. R holds elements.num_cells rotations (from
// fit_rotations), in the file's order like rhs.
void arap_rhs(const ArapElements& elements, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs);

} // namespace iarap
