#include "rotation_smoothing.h"

#include "iarap/core/errors.h"
#include "iarap/solver/polar_rotation.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <set>

namespace iarap::detail {

namespace {

Eigen::Matrix3d symmetric_part(const Eigen::Matrix3d& P) {
  return 0.5 * (P + P.transpose());
}

// R exp([omega]_x) (Rodrigues), orthonormal to rounding.
Eigen::Matrix3d retract(const Eigen::Matrix3d& R, const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (!(angle > 0)) return R;
  return R * Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

double dot(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i].dot(b[i]);
  return s;
}

} // namespace

Eigen::Matrix3d floored_inverse(const Eigen::Matrix3d& M) {
  constexpr double kFloor = 1e-6;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(M);
  const Eigen::Vector3d lambda = eigen.eigenvalues();
  const double top = lambda.cwiseAbs().maxCoeff();
  if (!(top > 0) || !std::isfinite(top)) return Eigen::Matrix3d::Zero();
  return eigen.eigenvectors() * lambda.cwiseMax(kFloor * top).cwiseInverse().asDiagonal() *
         eigen.eigenvectors().transpose();
}

double rest_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double area = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(),
                          c = V.row(F(f, 2)).transpose();
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

RotationSmoothing::RotationSmoothing(const ArapElements& el, const std::vector<int>& position, double alpha,
                                     double area)
    : cells_(el.num_cells) {
  std::vector<std::set<int>> neighbours(static_cast<size_t>(cells_));
  bool shared = el.arrays_released && el.cells_share_elements;
  if (el.arrays_released) // the cell graph release_element_arrays kept
    for (int c = 0; c < cells_; ++c)
      for (int k = el.cell_neighbour_start[static_cast<size_t>(c)];
           k < el.cell_neighbour_start[static_cast<size_t>(c) + 1]; ++k)
        neighbours[static_cast<size_t>(position[static_cast<size_t>(c)])].insert(
            position[static_cast<size_t>(el.cell_neighbour[static_cast<size_t>(k)])]);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const int begin = el.cell_start[static_cast<size_t>(e)], end = el.cell_start[static_cast<size_t>(e) + 1];
    for (int a = begin; a < end; ++a)
      for (int b = begin; b < end; ++b) {
        const int i = position[static_cast<size_t>(el.cell[static_cast<size_t>(a)])];
        const int j = position[static_cast<size_t>(el.cell[static_cast<size_t>(b)])];
        if (a != b) shared = true;
        if (i != j) neighbours[static_cast<size_t>(i)].insert(j); // an intrinsic loop edge is no pair
      }
  }
  if (!shared)
    throw InputError("ARAP: rotation_smoothing needs rotation cells that share elements; these elements have "
                     "one cell each (tetrahedral ARAP: one rotation per tetrahedron), so there is no "
                     "neighbour to smooth against. Use rotation_smoothing 0 on tetrahedral meshes");
  const double beta = alpha * area / 2.0;
  start_.assign(1, 0);
  for (int i = 0; i < cells_; ++i) {
    const auto& n_i = neighbours[static_cast<size_t>(i)];
    for (const int j : n_i) {
      neighbour_.push_back(j);
      const double d_i = static_cast<double>(n_i.size());
      const double d_j = static_cast<double>(neighbours[static_cast<size_t>(j)].size());
      k_.push_back(beta * (1.0 / (2.0 * d_i) + 1.0 / (2.0 * d_j)));
    }
    start_.push_back(static_cast<int>(neighbour_.size()));
  }
  // Greedy colouring in visit order: a cell takes the smallest colour none of its neighbours has.
  std::vector<int> colour(static_cast<size_t>(cells_), -1);
  int colours = 0;
  std::vector<char> taken;
  for (int i = 0; i < cells_; ++i) {
    taken.assign(static_cast<size_t>(colours) + 1, 0);
    for (int p = start_[static_cast<size_t>(i)]; p < start_[static_cast<size_t>(i) + 1]; ++p) {
      const int c = colour[static_cast<size_t>(neighbour_[static_cast<size_t>(p)])];
      if (c >= 0) taken[static_cast<size_t>(c)] = 1;
    }
    int c = 0;
    while (taken[static_cast<size_t>(c)]) ++c;
    colour[static_cast<size_t>(i)] = c;
    colours = std::max(colours, c + 1);
  }
  colour_start_.assign(static_cast<size_t>(colours) + 1, 0);
  for (const int c : colour) ++colour_start_[static_cast<size_t>(c) + 1];
  for (int c = 0; c < colours; ++c)
    colour_start_[static_cast<size_t>(c) + 1] += colour_start_[static_cast<size_t>(c)];
  colour_cell_.resize(static_cast<size_t>(cells_));
  std::vector<int> next(colour_start_.begin(), colour_start_.end() - 1);
  for (int i = 0; i < cells_; ++i)
    colour_cell_[static_cast<size_t>(next[static_cast<size_t>(colour[static_cast<size_t>(i)])]++)] = i;
}

double RotationSmoothing::energy(const std::vector<Eigen::Matrix3d>& R) const {
  double sum = 0.0;
  for (int i = 0; i < cells_; ++i)
    for (int p = start_[static_cast<size_t>(i)]; p < start_[static_cast<size_t>(i) + 1]; ++p) {
      const int j = neighbour_[static_cast<size_t>(p)];
      if (j > i)
        sum += k_[static_cast<size_t>(p)] *
               (R[static_cast<size_t>(i)] - R[static_cast<size_t>(j)]).squaredNorm();
    }
  return sum;
}

Eigen::Matrix3d RotationSmoothing::coupled_target(const std::vector<Eigen::Matrix3d>& S,
                                                  const std::vector<Eigen::Matrix3d>& R, int i) const {
  Eigen::Matrix3d T = S[static_cast<size_t>(i)];
  for (int p = start_[static_cast<size_t>(i)]; p < start_[static_cast<size_t>(i) + 1]; ++p)
    T += (2.0 * k_[static_cast<size_t>(p)]) * R[static_cast<size_t>(neighbour_[static_cast<size_t>(p)])];
  return T;
}

// f(R') - f(R) for f(R) = -sum_i tr(R_i^T S_i) + E_smooth(R), summed from per-cell and per-pair differences
// (tr((R'_i - R_i)^T S_i), (d' - d) : (d' + d) for d = R_i - R_j): accurate to rounding of the change
// itself, not of f, so that a step near the minimizer is judged on its true sign.
double RotationSmoothing::objective_change(const std::vector<Eigen::Matrix3d>& S,
                                           const std::vector<Eigen::Matrix3d>& R,
                                           const std::vector<Eigen::Matrix3d>& R_new) const {
  double change = 0.0;
  for (int i = 0; i < cells_; ++i) {
    const auto c = static_cast<size_t>(i);
    change -= (R_new[c] - R[c]).cwiseProduct(S[c]).sum();
    for (int p = start_[c]; p < start_[c + 1]; ++p) {
      const auto j = static_cast<size_t>(neighbour_[static_cast<size_t>(p)]);
      if (j <= c) continue;
      const Eigen::Matrix3d d = R[c] - R[j], d_new = R_new[c] - R_new[j];
      change +=
          k_[static_cast<size_t>(p)] * ((R_new[c] - R[c]) - (R_new[j] - R[j])).cwiseProduct(d_new + d).sum();
    }
  }
  return change;
}

void RotationSmoothing::sweep(const std::vector<Eigen::Matrix3d>& S, std::vector<Eigen::Matrix3d>& R) const {
  for (size_t c = 0; c + 1 < colour_start_.size(); ++c) {
    const int begin = colour_start_[c], end = colour_start_[c + 1];
#pragma omp parallel for schedule(static)
    for (int q = begin; q < end; ++q) {
      const int i = colour_cell_[static_cast<size_t>(q)];
      R[static_cast<size_t>(i)] = polar_rotation(coupled_target(S, R, i));
    }
  }
}

double RotationSmoothing::stationarity(const std::vector<Eigen::Matrix3d>& S,
                                       const std::vector<Eigen::Matrix3d>& R, std::vector<Eigen::Vector3d>& g,
                                       double& scale) const {
  g.resize(static_cast<size_t>(cells_));
  double largest = 0.0;
  scale = 0.0;
  for (int i = 0; i < cells_; ++i) {
    const Eigen::Matrix3d T = coupled_target(S, R, i);
    g[static_cast<size_t>(i)] = -vee_of_skew_part(R[static_cast<size_t>(i)].transpose() * T);
    largest = std::max(largest, g[static_cast<size_t>(i)].cwiseAbs().maxCoeff());
    scale = std::max(scale, T.norm());
  }
  return largest;
}

int RotationSmoothing::fit(const std::vector<Eigen::Matrix3d>& S, std::vector<Eigen::Matrix3d>& R) {
  // Stationary when every |g_i| is within 1e-12 of the largest |T_i| (rounding is ~1e-16 of it): the
  // rotations are then exact to ~1e-12 / lambda_min(H) |T|, far below what the envelope gradient needs.
  constexpr double kStationary = 1e-12;
  constexpr int kMaxSteps = 200;
  const bool cold = R.size() != static_cast<size_t>(cells_);
  if (cold) {
    R.resize(static_cast<size_t>(cells_));
    for (int i = 0; i < cells_; ++i) R[static_cast<size_t>(i)] = polar_rotation(S[static_cast<size_t>(i)]);
  }
  int steps = 0;
  if (cold) {
    sweep(S, R);
    ++steps;
  }
  std::vector<Eigen::Vector3d> g, omega, minus_g;
  std::vector<Eigen::Matrix3d> trial(R.size());
  while (steps < kMaxSteps) {
    double scale = 0.0;
    const double largest = stationarity(S, R, g, scale);
    if (largest <= kStationary * scale) break;
    // A Newton step on the rotation group, solved to a forcing term that tightens as g falls (Eisenstat &
    // Walker); CG from 0 stops at negative curvature, so the direction descends either way (where its
    // first step meets negative curvature, the preconditioned gradient). Halved until f decreases.
    prepare_tangent(S, R);
    minus_g.resize(g.size());
    for (size_t i = 0; i < g.size(); ++i) minus_g[i] = -g[i];
    const double forcing = std::min(0.1, std::sqrt(largest / scale));
    const int cg = conjugate_gradients(minus_g, omega, forcing, 500);
    if (cg == 0)
      for (size_t i = 0; i < g.size(); ++i) omega[i] = H_diagonal_inverse_[i] * minus_g[i];
    ++steps;
    bool accepted = false;
    for (double t = 1.0; t > 1e-3 && !accepted; t *= 0.5) {
      for (int i = 0; i < cells_; ++i)
        trial[static_cast<size_t>(i)] = retract(R[static_cast<size_t>(i)], t * omega[static_cast<size_t>(i)]);
      if (objective_change(S, R, trial) < 0) {
        R.swap(trial);
        accepted = true;
      }
    }
    if (!accepted) { // no decrease along it (at rounding, or a poor model): a Gauss-Seidel sweep instead
      trial = R;
      sweep(S, trial);
      if (!(objective_change(S, R, trial) < 0)) break; // neither step lowers f: stationary to rounding
      R.swap(trial);
    }
  }
  return steps;
}

void RotationSmoothing::prepare_tangent(const std::vector<Eigen::Matrix3d>& S,
                                        const std::vector<Eigen::Matrix3d>& R) {
  H_diagonal_.resize(static_cast<size_t>(cells_));
  H_diagonal_inverse_.resize(static_cast<size_t>(cells_));
  H_off_.resize(neighbour_.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < cells_; ++i) {
    const auto c = static_cast<size_t>(i);
    const Eigen::Matrix3d P = symmetric_part(R[c].transpose() * coupled_target(S, R, i));
    H_diagonal_[c] = P.trace() * Eigen::Matrix3d::Identity() - P;
    H_diagonal_inverse_[c] = floored_inverse(H_diagonal_[c]);
    for (int p = start_[c]; p < start_[c + 1]; ++p) {
      const Eigen::Matrix3d Q = R[c].transpose() * R[static_cast<size_t>(neighbour_[static_cast<size_t>(p)])];
      H_off_[static_cast<size_t>(p)] =
          (2.0 * k_[static_cast<size_t>(p)]) * (Q.transpose() - Q.trace() * Eigen::Matrix3d::Identity());
    }
  }
}

void RotationSmoothing::apply(const std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& y) const {
  y.resize(x.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < cells_; ++i) {
    const auto c = static_cast<size_t>(i);
    Eigen::Vector3d sum = H_diagonal_[c] * x[c];
    for (int p = start_[c]; p < start_[c + 1]; ++p)
      sum += H_off_[static_cast<size_t>(p)] * x[static_cast<size_t>(neighbour_[static_cast<size_t>(p)])];
    y[c] = sum;
  }
}

int RotationSmoothing::tangent_solve(const std::vector<Eigen::Vector3d>& a,
                                     std::vector<Eigen::Vector3d>& omega) const {
  return conjugate_gradients(a, omega, 1e-12, 20 * cells_ + 100);
}

// Preconditioned CG from x = 0 on H x = b, to |r| <= tolerance |b|. Stops early on a direction of
// non-positive curvature (H indefinite away from a minimizer), keeping the iterate so far.
int RotationSmoothing::conjugate_gradients(const std::vector<Eigen::Vector3d>& b,
                                           std::vector<Eigen::Vector3d>& x, double tolerance,
                                           int max_iterations) const {
  const size_t n = b.size();
  x.assign(n, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> r = b, z(n), p(n), Hp;
  for (size_t i = 0; i < n; ++i) z[i] = H_diagonal_inverse_[i] * r[i];
  p = z;
  double rz = dot(r, z);
  const double stop = tolerance * tolerance * dot(b, b);
  int iteration = 0;
  while (iteration < max_iterations && dot(r, r) > stop) {
    apply(p, Hp);
    const double curvature = dot(p, Hp);
    if (!(curvature > 0)) break;
    const double step = rz / curvature;
    for (size_t i = 0; i < n; ++i) {
      x[i] += step * p[i];
      r[i] -= step * Hp[i];
      z[i] = H_diagonal_inverse_[i] * r[i];
    }
    const double rz_next = dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
    ++iteration;
  }
  return iteration;
}

} // namespace iarap::detail
