#include "iarap/solver/fit_rotations.h"

#include "iarap/solver/polar_rotation.h"

#include "streamed_fit_rotations.h"
#include "streamed_layout.h"
#include "visit_order.h"

#include <algorithm>

namespace iarap {

namespace {
using detail::element_vectors;

// S += w (s s_hat^T), as w (s_i s_hat_j) rather than (w s_i) s_hat_j: at rest S is then bitwise symmetric,
// which polar_rotation turns into exactly R = I when S is positive definite.
inline void add_covariance(const detail::CellEntry& x, const double (&s)[3], const double (&s_hat)[3],
                           Eigen::Matrix3d& S) {
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) S(i, j) += x.w * (s[i] * s_hat[j]);
}
// The element's term of its cell's energy, (w / 2) |s - R s_hat|^2 (Eq. 1), from the residual itself.
inline double element_energy(const detail::CellEntry& x, const double (&s)[3], const double (&s_hat)[3],
                             const Eigen::Matrix3d& R) {
  double r2 = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double r = s[i] - (R(i, 0) * s_hat[0] + R(i, 1) * s_hat[1] + R(i, 2) * s_hat[2]);
    r2 += r * r;
  }
  return 0.5 * x.w * r2;
}
} // namespace

namespace detail {

void cell_covariances(const ArapElements& el, const ArapElements::ValueRows& U_rows,
                      std::vector<Eigen::Matrix3d>& S) {
  const StreamedLayout& sl = streamed(el);
  S.resize(static_cast<size_t>(el.num_cells));
  const double* u = U_rows.data();
  const double* v = sl.rest_rows.data();
#pragma omp parallel for schedule(dynamic, 256)
  for (int c = 0; c < el.num_cells; ++c) {
    Eigen::Matrix3d Sc = Eigen::Matrix3d::Zero();
    for (int k = sl.cell_entry_start[static_cast<size_t>(c)];
         k < sl.cell_entry_start[static_cast<size_t>(c) + 1]; ++k) {
      double s[3], s_hat[3];
      element_vectors(sl.cell_entry[static_cast<size_t>(k)], u, v, s, s_hat);
      add_covariance(sl.cell_entry[static_cast<size_t>(k)], s, s_hat, Sc);
    }
    S[static_cast<size_t>(c)] = Sc;
  }
}

void visit_rows(const ArapElements& el, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows) {
  const StreamedLayout& sl = streamed(el);
  const Eigen::Index nv = U.rows();
  U_rows.resize(nv, 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index p = 0; p < nv; ++p) {
    const Eigen::Index v = sl.visit_order[static_cast<size_t>(p)];
    for (int d = 0; d < 3; ++d) U_rows(p, d) = U(v, d);
  }
}

double fit_rotations_in_visit_order(const ArapElements& el, const ArapElements::ValueRows& U_rows,
                                    std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy,
                                    std::vector<Eigen::Matrix3d>* covariances) {
  const StreamedLayout& sl = streamed(el);
  const int n = el.num_cells;
  // The previous rotations are a start for the fit only when there is one per cell.
  const bool warm = R.size() == static_cast<size_t>(n);
  R.resize(static_cast<size_t>(n));
  cell_energy.resize(n);
  if (covariances) covariances->resize(static_cast<size_t>(n));
  const double* u = U_rows.data();
  const double* v = sl.rest_rows.data();
  const CellEntry* entry = sl.cell_entry.data();

  // Cells go in blocks of kBlock: their covariances first, then their rotations in one batched call
  // (polar_rotation_near fits four side by side), then their energies.
  constexpr int kBlock = 4;
  const int blocks = (n + kBlock - 1) / kBlock;
#pragma omp parallel for schedule(dynamic, 64)
  for (int block = 0; block < blocks; ++block) {
    const int first = block * kBlock, count = std::min(kBlock, n - first);
    // The first kKeep element vectors (current and rest) of each cell are kept for the energy sweep; longer
    // cells recompute the rest.
    constexpr int kKeep = 32;
    double kept[kBlock][kKeep][3], kept_hat[kBlock][kKeep][3];
    Eigen::Matrix3d S[kBlock], Rc[kBlock];
    for (int l = 0; l < count; ++l) {
      const auto c = static_cast<size_t>(first + l); // the cell at position c (ArapElements::visit_order)
      const int begin = sl.cell_entry_start[c];
      const int end = sl.cell_entry_start[c + 1];
      S[l].setZero(); // Eq. 15
      for (int k = begin; k < end; ++k) {
        const CellEntry& x = entry[k];
        double s[3], s_hat[3];
        element_vectors(x, u, v, s, s_hat);
        add_covariance(x, s, s_hat, S[l]);
        if (k - begin < kKeep)
          for (int d = 0; d < 3; ++d) kept[l][k - begin][d] = s[d], kept_hat[l][k - begin][d] = s_hat[d];
      }
    }
    if (el.planar)
      for (int l = 0; l < count; ++l) Rc[l] = planar_rotation(S[l]);
    else if (warm)
      polar_rotation_near(S, &R[static_cast<size_t>(first)], Rc, count);
    else
      for (int l = 0; l < count; ++l) Rc[l] = polar_rotation(S[l]);
    // The energy from the residuals themselves (not from tr(R^T S)): it stays accurate as it goes to zero,
    // which the stopping rule needs. The cells' entries are still in L1 from the sweep above.
    for (int l = 0; l < count; ++l) {
      const auto c = static_cast<size_t>(first + l);
      const int begin = sl.cell_entry_start[c];
      const int end = sl.cell_entry_start[c + 1];
      double energy = 0.0;
      for (int k = begin; k < end; ++k) {
        const CellEntry& x = entry[k];
        double s[3], s_hat[3];
        if (k - begin < kKeep) {
          for (int d = 0; d < 3; ++d) s[d] = kept[l][k - begin][d], s_hat[d] = kept_hat[l][k - begin][d];
        } else {
          element_vectors(x, u, v, s, s_hat);
        }
        energy += element_energy(x, s, s_hat, Rc[l]);
      }
      R[c] = Rc[l];
      if (covariances) (*covariances)[c] = S[l];
      cell_energy(sl.visit_order[c]) = energy;
    }
  }
  return cell_energy.sum();
}

double cell_energies_in_visit_order(const ArapElements& el, const ArapElements::ValueRows& U_rows,
                                    const std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy) {
  const StreamedLayout& sl = streamed(el);
  cell_energy.resize(el.num_cells);
  const double* u = U_rows.data();
  const double* v = sl.rest_rows.data();
#pragma omp parallel for schedule(dynamic, 256)
  for (int c = 0; c < el.num_cells; ++c) {
    double energy = 0.0;
    for (int k = sl.cell_entry_start[static_cast<size_t>(c)];
         k < sl.cell_entry_start[static_cast<size_t>(c) + 1]; ++k) {
      const CellEntry& x = sl.cell_entry[static_cast<size_t>(k)];
      double s[3], s_hat[3];
      element_vectors(x, u, v, s, s_hat);
      energy += element_energy(x, s, s_hat, R[static_cast<size_t>(c)]);
    }
    cell_energy(sl.visit_order[static_cast<size_t>(c)]) = energy;
  }
  return cell_energy.sum();
}

} // namespace detail

double fit_rotations(const ArapElements& el, const Eigen::MatrixXd& U, ArapElements::ValueRows& U_rows,
                     std::vector<Eigen::Matrix3d>& R, Eigen::VectorXd& cell_energy) {
  const auto n = static_cast<size_t>(el.num_cells);
  const std::vector<int>& order = detail::streamed(el).visit_order;
  detail::visit_rows(el, U, U_rows);
  std::vector<Eigen::Matrix3d> R_visit;
  if (R.size() == n) // a warm start only when there is one rotation per cell
    detail::to_visit_order(order, R, R_visit);
  const double energy = detail::fit_rotations_in_visit_order(el, U_rows, R_visit, cell_energy);
  detail::from_visit_order(order, R_visit, R);
  return energy;
}

} // namespace iarap
