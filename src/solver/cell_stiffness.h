// Stiffness (issue 45): a factor s_c > 0 on the energy of each rotation cell, E = sum_c s_c E_c. A cell's
// best rotation does not depend on s_c (s_c scales the cell's covariance S_c), so the factor changes only
// the weights of the cell's terms: the streamed layout's cell entries (w, read by the local step, the
// energy and the Hessian) and right-hand-side terms (R_c p_vc) scale by s_c, and L's element weight
// |cells(e)| w_e (Eq. 17) becomes (sum over c in cells(e) of s_c) w_e. Internal to the solver.
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>

namespace iarap::detail {

// True when s is empty or 1 everywhere: the energy without stiffness, bit for bit.
bool is_unit_stiffness(const Eigen::VectorXd& s);

// The factor of every cell of el from per-vertex factors (#V): vertex v's cell gets s_v; a boundary point
// that iARAP inserted (cells #V, #V + 1, ...) gets the mean over the vertices its elements' b reach.
Eigen::VectorXd cell_stiffness_of(const ArapElements& el, const Eigen::VectorXd& vertex_stiffness);

// Sets el.cell_stiffness and scales a new copy of el's streamed layout (copies of el share the old one).
void apply_cell_stiffness(ArapElements& el, Eigen::VectorXd cell_stiffness);

// sum over c in cells(e) of s_c: |cells(e)| when el has no stiffness.
inline double element_cell_weight(const ArapElements& el, Eigen::Index e) {
  const int begin = el.cell_start[static_cast<size_t>(e)], end = el.cell_start[static_cast<size_t>(e) + 1];
  if (el.cell_stiffness.size() == 0) return end - begin;
  double sum = 0.0;
  for (int k = begin; k < end; ++k) sum += el.cell_stiffness(el.cell[static_cast<size_t>(k)]);
  return sum;
}

} // namespace iarap::detail
