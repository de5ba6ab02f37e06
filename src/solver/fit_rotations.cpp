#include "iarap/solver/fit_rotations.h"

#include "iarap/solver/polar_rotation.h"

namespace iarap {

double fit_rotations(const ArapElements& el, const Eigen::MatrixXd& U, ArapElements::ValueRows& s,
                     std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy) {
  const Eigen::Index m = el.size();
  const int n = el.num_cells;
  s.resize(m, 3);
  R.resize(static_cast<size_t>(n));
  cell_energy.resize(n);

  // Deformed element vectors s_e = U^T b_e, summed in slot order exactly like s_hat (zero energy at rest).
#pragma omp parallel for schedule(static)
  for (Eigen::Index e = 0; e < m; ++e)
    for (int d = 0; d < 3; ++d) {
      double v = 0.0;
      for (int k = 0; k < 3; ++k)
        v += el.b_value(e, k) * U(el.b_index(e, k), d);
      s(e, d) = v;
    }

#pragma omp parallel for schedule(dynamic, 256)
  for (int c = 0; c < n; ++c) {
    const int begin = el.cell_element_start[c], end = el.cell_element_start[c + 1];
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero(); // Eq. 15
    for (int k = begin; k < end; ++k) {
      const int e = el.cell_element[k];
      const double w = el.w(e);
      // w (s_i s_hat_j) rather than (w s_i) s_hat_j: at rest S is then bitwise symmetric, which
      // polar_rotation turns into exactly R = I when S is positive definite.
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i)
          S(i, j) += w * (s(e, i) * el.s_hat(e, j));
    }
    const Eigen::Matrix3d Rc = polar_rotation(S);
    double energy = 0.0;
    for (int k = begin; k < end; ++k) {
      const int e = el.cell_element[k];
      const Eigen::Vector3d r = s.row(e).transpose() - Rc * el.s_hat.row(e).transpose();
      energy += 0.5 * el.w(e) * r.squaredNorm();
    }
    R[static_cast<size_t>(c)] = Rc;
    cell_energy(c) = energy;
  }
  return cell_energy.sum();
}

} // namespace iarap
