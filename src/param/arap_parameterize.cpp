#include "iarap/param/arap_parameterize.h"

#include "constrained_system.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/param/closest_rotation_2d.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/fixed_boundary_map.h"
#include "iarap/param/injective_step.h"
#include "iarap/param/lscm.h"

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace iarap {

namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void check_options(const ParamOptions& options) {
  if (options.max_iterations < 0)
    throw InputError("max_iterations must be >= 0; got " + std::to_string(options.max_iterations));
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance))
    throw InputError("tolerance must be a finite number >= 0; got " + std::to_string(options.tolerance));
  if (!(options.step_fraction > 0 && options.step_fraction < 1))
    throw InputError("step_fraction must lie in (0, 1); got " + std::to_string(options.step_fraction));
  if (!(options.barrier_weight > 0) || !std::isfinite(options.barrier_weight))
    throw InputError("barrier_weight must be a finite number > 0; got " +
                     std::to_string(options.barrier_weight));
  if (!(options.barrier_threshold > 0) || !std::isfinite(options.barrier_threshold))
    throw InputError("barrier_threshold must be a finite number > 0; got " +
                     std::to_string(options.barrier_threshold));
  if (options.boundary == ParamBoundary::Circle && options.init == ParamInit::Lscm)
    throw InputError(
        "a circular boundary needs an initial map with that boundary: tutte or harmonic, not lscm");
}

int flipped_triangles(const DiskMesh& disk, const Eigen::MatrixXd& UV) {
  int flipped = 0;
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f)
    if (!(face_jacobian(disk.frames, disk.F, UV, f).determinant() > 0)) ++flipped;
  return flipped;
}

Eigen::MatrixXd initial_map(const DiskMesh& disk, ParamInit init, const Eigen::MatrixXd& circle) {
  switch (init) {
  case ParamInit::Lscm:
    return lscm(disk);
  case ParamInit::Tutte:
    return fixed_boundary_map(disk, BoundaryMapWeights::Uniform, circle);
  case ParamInit::Harmonic:
    return fixed_boundary_map(disk, BoundaryMapWeights::Cotan, circle);
  }
  return {};
}

// The requested initial map, or Tutte's when the iteration is to stay flip-free and the requested one is
// not injective. Records which one in the report.
Eigen::MatrixXd starting_map(const DiskMesh& disk, const ParamOptions& options, ParamReport& report) {
  const Eigen::MatrixXd circle = circle_boundary(disk);
  Eigen::MatrixXd UV = initial_map(disk, options.init, circle);
  report.requested_init = report.init = options.init;
  report.init_flipped = flipped_triangles(disk, UV);
  if (!options.allow_flips && report.init_flipped > 0 && options.init != ParamInit::Tutte) {
    UV = initial_map(disk, ParamInit::Tutte, circle);
    report.init = ParamInit::Tutte;
    report.init_fallback = true;
  }
  return UV;
}

// The barrier that keeps the flip-free iteration away from det J = 0: per face area_f mu psi(det J_f),
// psi(x) = -log(x / eps) + x / eps - 1 below eps (zero with zero slope at eps), +infinity at x <= 0.
struct Barrier {
  double weight = 0;    // mu; 0: no barrier (the plain iteration)
  double threshold = 1; // eps

  double value(double det) const {
    if (weight == 0 || det >= threshold) return 0;
    if (!(det > 0)) return std::numeric_limits<double>::infinity();
    return weight * (-std::log(det / threshold) + det / threshold - 1);
  }
  double slope(double det) const { // d value / d det, for det > 0
    if (weight == 0 || det >= threshold) return 0;
    return weight * (1 / threshold - 1 / det);
  }
};

Eigen::Matrix2d row_matrix(const Eigen::MatrixXd& rows, Eigen::Index f) {
  Eigen::Matrix2d M;
  M << rows(f, 0), rows(f, 1), rows(f, 2), rows(f, 3);
  return M;
}

// The iteration on one mesh: the Jacobians J_f of the current map, their closest rotations R_f, and the
// factorized cotan Laplacian L with the pinned vertices held. A step solves L d = -grad W / 2 for the map
// increment d, W = E + barrier. Without the barrier U + d is exactly the global step's solution
// (L (U + d) = sum_f area_f D_f R_f^T) and t = 1 is the plain local/global iteration; with it, d is the
// same Laplacian-preconditioned descent direction for W (as in SLIM, Rabinovich et al. 2017), whose
// barrier turns the direction away from triangles about to degenerate.
class TriangleArap {
public:
  // flip_fraction: 0 for the plain iteration, else the fraction of the largest injective step to take.
  TriangleArap(const DiskMesh& disk, const std::vector<int>& pinned, Barrier barrier, double flip_fraction)
      : disk_(disk), barrier_(barrier), flip_fraction_(flip_fraction),
        system_(cotan_laplacian(disk.V, disk.F), pinned, "the ARAP parameterization system") {}

  // Sets the current map; returns its ARAP energy.
  double start(const Eigen::MatrixXd& UV) {
    J_ = face_jacobians(disk_.frames, disk_.F, UV);
    R_.resize(J_.rows(), 4);
    total_ = evaluate(J_, R_, energy_);
    return energy_;
  }

  // One step from UV (the map start() or the last step left): UV += t d with t = 1 (plain), or when
  // flip-free, t = min(1, flip_fraction * t_max) (t_max: the first step at which a triangle
  // degenerates), halved until W decreases by Armijo's rule (t = 0 when 40 halvings do not reach it).
  // Returns the ARAP energy of the new map and sets step to t.
  double step(Eigen::MatrixXd& UV, double& step) {
    assemble_rhs();
    d_.setZero(rhs_.rows(), 2);
    system_.solve(rhs_, d_);
    face_jacobians(disk_.frames, disk_.F, d_, dJ_);
    R_try_.resize(J_.rows(), 4);
    double energy = 0, total = 0;
    step = 1;
    if (flip_fraction_ == 0) {
      J_try_.noalias() = J_ + dJ_;
      total = evaluate(J_try_, R_try_, energy);
    } else {
      step = std::min(1.0, flip_fraction_ * largest_injective_step());
      const double descent = -2 * (rhs_.array() * d_.array()).sum(); // grad W . d
      for (int halving = 0;; ++halving, step *= 0.5) {
        if (halving == max_halvings) {
          step = 0;
          return energy_;
        }
        J_try_.noalias() = J_ + step * dJ_;
        total = evaluate(J_try_, R_try_, energy);
        if (total <= total_ + armijo * step * descent) break;
      }
    }
    UV += step * d_;
    J_.swap(J_try_);
    R_.swap(R_try_);
    total_ = total;
    energy_ = energy;
    return energy_;
  }

private:
  static constexpr double armijo = 1e-4;
  static constexpr int max_halvings = 40;

  // R = closest_rotation_2d(J_f) per face; energy = sum_f area_f ||J_f - R_f||^2; returns energy + barrier.
  double evaluate(const Eigen::MatrixXd& J, Eigen::MatrixXd& R, double& energy) const {
    double total = 0;
    energy = 0;
    for (Eigen::Index f = 0; f < J.rows(); ++f) {
      const Eigen::Matrix2d Jf = row_matrix(J, f), Rf = closest_rotation_2d(Jf);
      R.row(f) << Rf(0, 0), Rf(0, 1), Rf(1, 0), Rf(1, 1);
      const double e = disk_.frames.area(f) * (Jf - Rf).squaredNorm();
      energy += e;
      total += e + disk_.frames.area(f) * barrier_.value(Jf.determinant());
    }
    return total;
  }

  // rhs = -grad W / 2 at the current map: per face G_f = area_f (2 (J_f - R_f) + psi'(det J_f) cof J_f)
  // = dW_f / dJ_f, and vertex F(f, c) gets -(D_f G_f^T) row c / 2.
  void assemble_rhs() {
    rhs_.setZero(disk_.V.rows(), 2);
    for (Eigen::Index f = 0; f < disk_.F.rows(); ++f) {
      const Eigen::Matrix2d J = row_matrix(J_, f), R = row_matrix(R_, f);
      Eigen::Matrix2d cofactor;
      cofactor << J(1, 1), -J(1, 0), -J(0, 1), J(0, 0);
      const Eigen::Matrix2d half_G =
          disk_.frames.area(f) * ((J - R) + 0.5 * barrier_.slope(J.determinant()) * cofactor);
      for (int c = 0; c < 3; ++c) {
        const double dx = disk_.frames.D(f, 2 * c), dy = disk_.frames.D(f, 2 * c + 1);
        rhs_(disk_.F(f, c), 0) -= half_G(0, 0) * dx + half_G(0, 1) * dy;
        rhs_(disk_.F(f, c), 1) -= half_G(1, 0) * dx + half_G(1, 1) * dy;
      }
    }
  }

  // min_f first_degenerate_step(J_f, J_f + dJ_f): +infinity when no triangle degenerates along the line.
  double largest_injective_step() const {
    double t = std::numeric_limits<double>::infinity();
    for (Eigen::Index f = 0; f < J_.rows(); ++f)
      t = std::min(t, first_degenerate_step(row_matrix(J_, f), row_matrix(J_, f) + row_matrix(dJ_, f)));
    return t;
  }

  const DiskMesh& disk_;
  Barrier barrier_;
  double flip_fraction_;
  param_detail::ConstrainedSystem system_;
  Eigen::MatrixXd J_, dJ_, J_try_, R_, R_try_; // #F x 4, row by row
  Eigen::MatrixXd rhs_, d_;                    // #V x 2
  double energy_ = 0, total_ = 0;              // E and W of the current map
};

std::vector<int> pinned_vertices(const DiskMesh& disk, ParamBoundary boundary) {
  if (boundary == ParamBoundary::Free) return {disk.boundary.front()};
  std::vector<int> pinned = disk.boundary;
  std::sort(pinned.begin(), pinned.end());
  return pinned;
}

} // namespace

ParamResult arap_parameterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const ParamOptions& options) {
  const auto total_start = Clock::now();
  check_options(options);
  ParamResult result;
  ParamReport& report = result.report;
  // Exact power-of-two scaling: the solve sees coordinates near 1 whatever the units (areas of a mesh at
  // 1e200 would overflow); UV scales back by s, energies by s^2.
  const double s = V.cols() == 3 ? normalizing_scale(V) : 1.0;
  const DiskMesh disk = prepare_disk(V / s, F);
  report.check_ms = elapsed_ms(total_start);

  auto phase_start = Clock::now();
  Eigen::MatrixXd UV = starting_map(disk, options, report);
  report.init_ms = elapsed_ms(phase_start);

  phase_start = Clock::now();
  const std::vector<int> pinned = pinned_vertices(disk, options.boundary);
  report.pinned = static_cast<int>(pinned.size());
  Barrier barrier;
  if (!options.allow_flips) {
    barrier.weight = options.barrier_weight;
    barrier.threshold = options.barrier_threshold;
  }
  TriangleArap arap(disk, pinned, barrier, options.allow_flips ? 0.0 : options.step_fraction);
  report.factor_ms = elapsed_ms(phase_start);

  phase_start = Clock::now();
  double energy = arap.start(UV);
  report.initial_energy = energy * s * s;
  for (int k = 0; k < options.max_iterations; ++k) {
    double t = 1;
    const double next = arap.step(UV, t);
    report.energies.push_back(next * s * s);
    report.steps.push_back(t);
    report.iterations = k + 1;
    const bool small_decrease = energy - next <= options.tolerance * energy;
    energy = next;
    if (small_decrease) {
      report.converged = true;
      break;
    }
  }
  report.iterate_ms = elapsed_ms(phase_start);

  report.distortion = map_distortion(disk.frames, disk.F, UV);
  report.distortion.energy *= s * s;
  report.distortion.scaled_energy *= s * s;
  result.UV = UV * s;
  report.total_ms = elapsed_ms(total_start);
  return result;
}

} // namespace iarap
