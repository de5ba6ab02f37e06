#include "iarap/solver/arap_rhs.h"

#include "visit_order.h"

namespace iarap {

void arap_rhs_in_visit_order(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs) {
  const int n = el.num_vertices;
  rhs.resize(n, 3);
  const ArapElements::RhsTerm* term = el.rhs_term.data();
  // rhs_v = sum_c R_c p_vc: each vertex gathers its own terms, so the loop is parallel without atomics.
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    double acc[3] = {0.0, 0.0, 0.0};
    for (int k = el.rhs_term_start[static_cast<size_t>(v)]; k < el.rhs_term_start[static_cast<size_t>(v) + 1]; ++k) {
      const ArapElements::RhsTerm& t = term[k];
      const Eigen::Matrix3d& Rc = R[static_cast<size_t>(t.cell)];
      for (int i = 0; i < 3; ++i) acc[i] += Rc(i, 0) * t.p[0] + Rc(i, 1) * t.p[1] + Rc(i, 2) * t.p[2];
    }
    for (int d = 0; d < 3; ++d) rhs(v, d) = acc[d];
  }
}

void arap_rhs(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R, Eigen::MatrixXd& rhs) {
  std::vector<Eigen::Matrix3d> R_visit;
  detail::rotations_to_visit_order(el, R, R_visit);
  Eigen::MatrixXd rhs_visit;
  arap_rhs_in_visit_order(el, R_visit, rhs_visit);
  rhs.resize(rhs_visit.rows(), 3);
  for (Eigen::Index p = 0; p < rhs_visit.rows(); ++p) rhs.row(el.visit_order[static_cast<size_t>(p)]) = rhs_visit.row(p);
}

} // namespace iarap
