// The right-hand side of the global step (Eq. 16) over the streamed layout, one vertex at a time, with the
// rotations in visit order: for passes that fuse it with other work (LocalGlobalProblem). Internal to the
// solver; arap_rhs (arap_rhs.h) is the public form.
#pragma once
#include "streamed_layout.h"

#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// Row p of the right-hand side in visit order (the vertex at position p): sum_c R_c p_vc over its terms
// (RhsTerm), R[c] the rotation of the cell at position c.
inline void arap_rhs_row(const StreamedLayout& sl, const std::vector<Eigen::Matrix3d>& R, int p,
                         double (&row)[3]) {
  row[0] = row[1] = row[2] = 0.0;
  const auto v = static_cast<size_t>(p);
  for (int k = sl.rhs_term_start[v]; k < sl.rhs_term_start[v + 1]; ++k) {
    const RhsTerm& t = sl.rhs_term[static_cast<size_t>(k)];
    const Eigen::Matrix3d& Rc = R[static_cast<size_t>(t.cell)];
    for (int i = 0; i < 3; ++i) row[i] += Rc(i, 0) * t.p[0] + Rc(i, 1) * t.p[1] + Rc(i, 2) * t.p[2];
  }
}

} // namespace iarap::detail
