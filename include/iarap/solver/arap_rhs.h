// Right-hand side of the ARAP global step (paper Eq. 16), gathered per vertex.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>
#include <vector>

namespace iarap {

// rhs (#V x 3) with row v = sum_e w_e (b_e)_v ((sum_{c in cells(e)} R_c) s_hat_e)^T (Eq. 16; the paper's
// (R_i + R_j) / 2 times the 2 cells of L = 2 B^T D_w B), evaluated as sum_c R_c p_vc over the vertex's
// (cell, p_vc) terms (ArapElements::rhs_term). R holds elements.num_cells rotations (from fit_rotations).
// R and rhs in the file's order; the iterations keep theirs in visit order and call arap_rhs_in_visit_order,
// which this wraps.
void arap_rhs(const ArapElements& elements, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs);

// arap_rhs in visit order (ArapElements::visit_order): R[p] is the rotation of cell visit_order[p], row p of
// rhs belongs to vertex visit_order[p]. One forward sweep, parallel over vertices without atomics, nothing
// allocated once rhs has its size.
void arap_rhs_in_visit_order(const ArapElements& elements, const std::vector<Eigen::Matrix3d>& R,
                             Eigen::MatrixXd& rhs);

// Row p of arap_rhs_in_visit_order (the vertex at position p), for passes that fuse it with other work.
inline void arap_rhs_row(const ArapElements& elements, const std::vector<Eigen::Matrix3d>& R, int p,
                         double (&row)[3]) {
  row[0] = row[1] = row[2] = 0.0;
  const auto v = static_cast<size_t>(p);
  for (int k = elements.rhs_term_start[v]; k < elements.rhs_term_start[v + 1]; ++k) {
    const ArapElements::RhsTerm& t = elements.rhs_term[static_cast<size_t>(k)];
    const Eigen::Matrix3d& Rc = R[static_cast<size_t>(t.cell)];
    for (int i = 0; i < 3; ++i) row[i] += Rc(i, 0) * t.p[0] + Rc(i, 1) * t.p[1] + Rc(i, 2) * t.p[2];
  }
}

} // namespace iarap
