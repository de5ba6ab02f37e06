#include "iarap/solver/arap_rhs.h"

#include "streamed_rhs.h"
#include "visit_order.h"

namespace iarap {

void arap_rhs(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs) {
  const detail::StreamedLayout& sl = detail::streamed(el);
  std::vector<Eigen::Matrix3d> R_visit;
  detail::to_visit_order(sl.visit_order, R, R_visit);
  const int n = el.num_vertices;
  rhs.resize(n, 3);
  // rhs_v = sum_c R_c p_vc: each vertex gathers its own terms, so the loop is parallel without atomics.
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    double row[3];
    detail::arap_rhs_row(sl, R_visit, p, row);
    for (int d = 0; d < 3; ++d) rhs(sl.visit_order[static_cast<size_t>(p)], d) = row[d];
  }
}

} // namespace iarap
