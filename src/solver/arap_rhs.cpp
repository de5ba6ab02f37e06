#include "iarap/solver/arap_rhs.h"

namespace iarap {

void arap_rhs(const ArapElements& el, const std::vector<Eigen::Matrix3d>& R, ArapElements::ValueRows& q,
              Eigen::MatrixXd& rhs) {
  const Eigen::Index m = el.size();
  const int n = el.num_vertices;
  q.resize(m, 3);
  rhs.resize(n, 3);

  // q_e = w_e (sum_{c in cells(e)} R_c) s_hat_e
#pragma omp parallel for schedule(static)
  for (Eigen::Index e = 0; e < m; ++e) {
    Eigen::Matrix3d Rsum = Eigen::Matrix3d::Zero();
    for (int c = el.cell_start[e]; c < el.cell_start[e + 1]; ++c)
      Rsum += R[static_cast<size_t>(el.cell[c])];
    q.row(e) = (el.w(e) * (Rsum * el.s_hat.row(e).transpose())).transpose();
  }

  // rhs_v = sum over the elements with (b_e)_v != 0 of (b_e)_v q_e
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    double acc[3] = {0.0, 0.0, 0.0};
    for (int k = el.vertex_slot_start[v]; k < el.vertex_slot_start[v + 1]; ++k) {
      const int slot = el.vertex_slot[k];
      const int e = slot / 3;
      const double b = el.b_value(e, slot % 3);
      for (int d = 0; d < 3; ++d)
        acc[d] += b * q(e, d);
    }
    for (int d = 0; d < 3; ++d)
      rhs(v, d) = acc[d];
  }
}

} // namespace iarap
