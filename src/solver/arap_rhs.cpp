#include "iarap/solver/arap_rhs.h"

#include "visit_order.h"

namespace iarap {

void arap_rhs_in_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R,
                             Eigen::MatrixXd& rhs) {
  const int n = el.num_vertices;
  rhs.resize(n, 3);
  // rhs_v = sum_c R_c p_vc: each vertex gathers its own terms, so the loop is parallel without atomics.
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    double row[3];
    arap_rhs_row(el, R, v, row);
    for (int d = 0; d < 3; ++d) rhs(v, d) = row[d];
  }
}

void arap_rhs(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs) {
  std::vector<Eigen::Matrix3d> R_visit;
  detail::rotations_to_visit_order(el, R, R_visit);
  Eigen::MatrixXd rhs_visit;
  arap_rhs_in_visit_order(el, R_visit, rhs_visit);
  rhs.resize(rhs_visit.rows(), 3);
  for (Eigen::Index p = 0; p < rhs_visit.rows(); ++p)
    rhs.row(el.visit_order[static_cast<size_t>(p)]) = rhs_visit.row(p);
}

} // namespace iarap
