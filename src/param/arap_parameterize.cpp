#include "iarap/param/arap_parameterize.h"

#include "iarap/core/stopwatch.h"

#include "../solver/anderson_acceleration.h"
#include "constrained_system.h"

#include "iarap/core/errors.h"
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/fixed_boundary_map.h"
#include "iarap/param/injective_step.h"
#include "iarap/param/lscm.h"
#include "iarap/param/planar_cells.h"
#include "iarap/solver/arap_elements.h"
#include "iarap/solver/closest_rotation_2d.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace iarap {

namespace {

void check_options(const ParamOptions& options) {
  if (options.max_iterations < 0)
    throw InputError("max_iterations must be >= 0; got " + std::to_string(options.max_iterations));
  if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance))
    throw InputError("tolerance must be a finite number >= 0; got " + std::to_string(options.tolerance));
  if (!(options.step_fraction > 0 && options.step_fraction < 1))
    throw InputError("step_fraction must lie in (0, 1); got " + std::to_string(options.step_fraction));
  if (options.barrier_weight && (!(*options.barrier_weight > 0) || !std::isfinite(*options.barrier_weight)))
    throw InputError("barrier_weight must be a finite number > 0; got " +
                     std::to_string(*options.barrier_weight));
  if (!(options.barrier_threshold > 0) || !std::isfinite(options.barrier_threshold))
    throw InputError("barrier_threshold must be a finite number > 0; got " +
                     std::to_string(options.barrier_threshold));
  if (options.anderson_window < 1)
    throw InputError("anderson_window must be >= 1; got " + std::to_string(options.anderson_window));
  // Measured (docs/param.md): on the flip-free steps, each bounded by the nearest degenerate triangle, the
  // mixed maps were rejected (0-2 of 13-144 iterations) or, approached the same way, stopped with a worse
  // map (lion, iarap: 0.927 against 0.873).
  if (options.accelerator == ParamAccelerator::Anderson && !options.allow_flips)
    throw InputError("the anderson accelerator applies to the plain iteration (allow_flips); the flip-free "
                     "steps are bounded by the nearest degenerate triangle, where the mixing does not help");
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

// The pins of the iteration in the disk's scaled units (arap_parameterize divides V by s).
UvPins scaled_pins(const UvPins& pins, double s) {
  UvPins scaled = pins;
  scaled.uv /= s;
  return scaled;
}

// With a free boundary, one or two pins are met by moving any start map: the orientation-preserving
// similarity z -> a z + b (complex numbers) that puts the pinned vertices on their positions (a = 1 for
// one pin). It keeps injectivity, and LSCM's map with the two pins held is exactly its default map moved
// so (the conformal energy is invariant to similarities). Throws InputError for two pins at one position.
void move_onto_pins(const UvPins& pins, Eigen::MatrixXd& UV) {
  using Complex = std::complex<double>;
  auto at = [&UV](int v) { return Complex(UV(v, 0), UV(v, 1)); };
  auto target = [&pins](Eigen::Index p) { return Complex(pins.uv(p, 0), pins.uv(p, 1)); };
  Complex a = 1;
  if (pins.size() == 2) {
    if (target(0) == target(1))
      throw InputError("pins 0 and 1 (vertices " + std::to_string(pins.vertices(0)) + " and " +
                       std::to_string(pins.vertices(1)) +
                       ") are at one UV position, which folds every triangle; give them distinct positions");
    a = (target(1) - target(0)) / (at(pins.vertices(1)) - at(pins.vertices(0)));
  }
  const Complex b = target(0) - a * at(pins.vertices(0));
  for (Eigen::Index v = 0; v < UV.rows(); ++v) {
    const Complex z = a * at(static_cast<int>(v)) + b;
    UV.row(v) << z.real(), z.imag();
  }
  // The similarity meets the pins up to rounding; the iteration holds them exactly.
  for (Eigen::Index p = 0; p < pins.size(); ++p) UV.row(pins.vertices(p)) = pins.uv.row(p);
}

// Whether the pins are held by the maps' linear systems (three or more with a free boundary, any with the
// circle) rather than met by moving the map (move_onto_pins).
bool pins_in_system(ParamBoundary boundary, const UvPins& pins) {
  return boundary == ParamBoundary::Circle || pins.size() >= 3;
}

// The initial map holding the pins: LSCM with them or the circle maps with them as inner vertices (see
// pins_in_system), else the unpinned map moved onto them.
Eigen::MatrixXd initial_map(const DiskMesh& disk, ParamInit init, ParamBoundary boundary,
                            const UvPins& pins) {
  const bool held = pins_in_system(boundary, pins);
  Eigen::MatrixXd UV;
  switch (init) {
  case ParamInit::Lscm:
    UV = held ? lscm(disk, pins) : lscm(disk);
    break;
  case ParamInit::Tutte:
  case ParamInit::Harmonic:
    UV = fixed_boundary_map(
        disk, init == ParamInit::Tutte ? BoundaryMapWeights::Uniform : BoundaryMapWeights::Cotan,
        circle_boundary(disk), held ? pins : UvPins{});
    break;
  }
  if (!held && pins.size() > 0) move_onto_pins(pins, UV);
  return UV;
}

bool on_boundary(const DiskMesh& disk, int v) {
  return std::find(disk.boundary.begin(), disk.boundary.end(), v) != disk.boundary.end();
}

// The requested initial map, or Tutte's when the iteration is to stay flip-free and the requested one is
// not injective and Tutte's can hold the pins (not with three or more pins one of which is on the boundary,
// which Tutte's map puts on the circle). Records which one in the report. Throws InputError when the
// flip-free iteration is left with a start the pins fold.
Eigen::MatrixXd starting_map(const DiskMesh& disk, const ParamOptions& options, const UvPins& pins,
                             ParamReport& report) {
  Eigen::MatrixXd UV = initial_map(disk, options.init, options.boundary, pins);
  report.requested_init = report.init = options.init;
  report.init_flipped = flipped_triangles(disk, UV);
  if (options.allow_flips || report.init_flipped == 0) return UV;
  const bool tutte_holds_pins = !pins_in_system(options.boundary, pins) ||
                                std::none_of(pins.vertices.begin(), pins.vertices.end(),
                                             [&disk](int v) { return on_boundary(disk, v); });
  int flipped = report.init_flipped;
  if (options.init != ParamInit::Tutte && tutte_holds_pins) {
    UV = initial_map(disk, ParamInit::Tutte, options.boundary, pins);
    report.init = ParamInit::Tutte;
    report.init_fallback = true;
    flipped = flipped_triangles(disk, UV);
  }
  // Tutte's map of a disk is injective, and so is any similarity of it (a fold left is floating point,
  // handled by the barrier's slope); with pins in its system it need not be, and no step of the iteration
  // can unfold what the pins hold folded.
  if (flipped > 0 && pins_in_system(options.boundary, pins) && pins.size() > 0)
    throw InputError("the " + param_init_name(report.init) + " map holding the " +
                     std::to_string(pins.size()) + " pins folds " + std::to_string(flipped) +
                     " triangles (det J <= 0); the flip-free iteration needs an injective start that holds "
                     "the pins: move or drop pins, or allow flips");
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
  // d value / d det for det > 0; 0 for det <= 0, where the barrier is infinite: a triangle flipped already
  // (a start whose Tutte map degenerates in floating point) is left to the energy, not pushed further.
  double slope(double det) const {
    if (weight == 0 || det >= threshold || !(det > 0)) return 0;
    return weight * (1 / threshold - 1 / det);
  }
};

// The vertices the global step holds: the user's pins, or with a free boundary and none of them the first
// boundary vertex (the energy is translation invariant), plus the whole boundary when it is a circle.
std::vector<int> pinned_vertices(const DiskMesh& disk, ParamBoundary boundary, const UvPins& pins) {
  std::vector<int> pinned(pins.vertices.begin(), pins.vertices.end());
  if (boundary == ParamBoundary::Circle)
    pinned.insert(pinned.end(), disk.boundary.begin(), disk.boundary.end());
  else if (pinned.empty())
    pinned.push_back(disk.boundary.front());
  std::sort(pinned.begin(), pinned.end());
  return pinned;
}

Eigen::Matrix2d row_matrix(const Eigen::MatrixXd& rows, Eigen::Index f) {
  Eigen::Matrix2d M;
  M << rows(f, 0), rows(f, 1), rows(f, 2), rows(f, 3);
  return M;
}

// The energies the iteration minimizes, each as: the system matrix M and the vector r(R) with
// grad E = 2 (M U - r(R)) at fixed rotations R (so the global step solves M U = r), and the energy of a map
// with its rotations fitted.

// Liu et al.'s per-triangle energy: M = the cotan Laplacian, r = sum_f area_f D_f R_f^T, rotations per face.
class TriangleEnergy {
public:
  explicit TriangleEnergy(const DiskMesh& disk) : disk_(disk), M_(cotan_laplacian(disk.V, disk.F)) {}

  const Eigen::SparseMatrix<double>& system() const { return M_; }

  double fit(const Eigen::MatrixXd& /*U*/, const Eigen::MatrixXd& J, Eigen::MatrixXd& R) const {
    R.resize(J.rows(), 4);
    double energy = 0;
    for (Eigen::Index f = 0; f < J.rows(); ++f) {
      const Eigen::Matrix2d Jf = row_matrix(J, f), Rf = closest_rotation_2d(Jf);
      R.row(f) << Rf(0, 0), Rf(0, 1), Rf(1, 0), Rf(1, 1);
      energy += disk_.frames.area(f) * (Jf - Rf).squaredNorm();
    }
    return energy;
  }

  void rhs(const Eigen::MatrixXd& R, Eigen::MatrixXd& r) const {
    r.setZero(disk_.V.rows(), 2);
    for (Eigen::Index f = 0; f < disk_.F.rows(); ++f) {
      const double a = disk_.frames.area(f);
      for (int c = 0; c < 3; ++c) {
        const double dx = disk_.frames.D(f, 2 * c), dy = disk_.frames.D(f, 2 * c + 1);
        r(disk_.F(f, c), 0) += a * (R(f, 0) * dx + R(f, 1) * dy);
        r(disk_.F(f, c), 1) += a * (R(f, 2) * dx + R(f, 3) * dy);
      }
    }
  }

private:
  const DiskMesh& disk_;
  Eigen::SparseMatrix<double> M_;
};

// A per-vertex energy on flattened cells (planar_cells.h): M = element_system_matrix / 2, rotations per
// vertex.
class CellEnergy {
public:
  explicit CellEnergy(PlanarCells cells)
      : cells_(std::move(cells)), M_(0.5 * element_system_matrix(cells_.elements)) {}

  const Eigen::SparseMatrix<double>& system() const { return M_; }

  double fit(const Eigen::MatrixXd& U, const Eigen::MatrixXd& /*J*/, Eigen::MatrixXd& R) const {
    return planar_cell_energy(cells_, U, R);
  }

  void rhs(const Eigen::MatrixXd& R, Eigen::MatrixXd& r) const { planar_cell_rhs(cells_, R, r); }

private:
  PlanarCells cells_;
  Eigen::SparseMatrix<double> M_;
};

// The iteration on one mesh and energy: the current map U, the Jacobians J_f of its triangles, the fitted
// rotations, and the factorized M with the pinned vertices held. A step solves M d = -grad W / 2 for the
// map increment d, W = E + barrier on the triangles' det J. Without the barrier U + d is exactly the
// global step's solution (M (U + d) = r(R)) and t = 1 is the plain local/global iteration; with it, d is
// the same preconditioned descent direction for W (as in SLIM, Rabinovich et al. 2017), whose barrier
// turns the direction away from triangles about to degenerate.
template <typename Energy> class Iteration {
public:
  // flip_fraction: 0 for the plain iteration, else the fraction of the largest injective step to take.
  // anderson_window: 0 for none, else the history of the Anderson mixing applied after each step.
  Iteration(const DiskMesh& disk, Energy energy, const std::vector<int>& pinned, Barrier barrier,
            double flip_fraction, int anderson_window)
      : disk_(disk), energy_(std::move(energy)), barrier_(barrier), flip_fraction_(flip_fraction),
        system_(energy_.system(), pinned, "the ARAP parameterization system") {
    if (anderson_window > 0) anderson_.emplace(anderson_window, 2 * disk.V.rows());
  }

  // Sets the current map; returns its energy.
  double start(const Eigen::MatrixXd& UV) {
    U_ = UV;
    face_jacobians(disk_.frames, disk_.F, U_, J_);
    W_ = evaluate(U_, J_, R_, E_);
    return E_;
  }

  const Eigen::MatrixXd& map() const { return U_; }

  // One step: U += t d with t = 1 (plain), or when flip-free, t = min(1, flip_fraction * t_max) (t_max:
  // the first step at which a triangle degenerates), halved until W decreases by Armijo's rule (t = 0 when
  // 40 halvings do not reach it). Returns the energy of the new map and sets step to t.
  double step(double& step) {
    const double W_before = W_;
    if (anderson_) U_before_ = U_;
    descend(step);
    if (anderson_ && step > 0) accelerate(W_before);
    return E_;
  }

  int accepted_mixings() const { return accepted_mixings_; }

private:
  static constexpr double armijo = 1e-4;
  static constexpr int max_halvings = 40;

  // Safeguarded Anderson mixing (Peng et al. 2018 for local/global solvers) of the plain iteration: the
  // steps so far, seen as the fixed-point map U -> U + d, extrapolate to a candidate, kept only when its
  // energy is below the previous iterate's (so E still decreases every iteration), else the history is
  // dropped. Pinned rows are the same in U and in every step, so the mixing keeps them exactly.
  void accelerate(double W_before) {
    if (!anderson_->step(U_before_.data(), U_.data(), U_try_.data())) return;
    face_jacobians(disk_.frames, disk_.F, U_try_, J_try_);
    double energy = 0;
    const double total = evaluate(U_try_, J_try_, R_try_, energy);
    if (!(total < W_before)) {
      anderson_->reset();
      return;
    }
    U_.swap(U_try_);
    J_.swap(J_try_);
    R_.swap(R_try_);
    W_ = total;
    E_ = energy;
    ++accepted_mixings_;
  }

  // The step itself (see step()); E_, W_ and the map become the new ones.
  void descend(double& step) {
    assemble_rhs();
    d_.setZero(rhs_.rows(), 2);
    system_.solve(rhs_, d_);
    face_jacobians(disk_.frames, disk_.F, d_, dJ_);
    double energy = 0, total = 0;
    step = 1;
    if (flip_fraction_ == 0) {
      try_step(step, energy, total);
    } else {
      step = std::min(1.0, flip_fraction_ * largest_injective_step());
      const double descent = -2 * (rhs_.array() * d_.array()).sum(); // grad W . d
      for (int halving = 0;; ++halving, step *= 0.5) {
        if (halving == max_halvings) {
          step = 0;
          return;
        }
        try_step(step, energy, total);
        if (total <= W_ + armijo * step * descent) break;
      }
    }
    U_.swap(U_try_);
    J_.swap(J_try_);
    R_.swap(R_try_);
    W_ = total;
    E_ = energy;
  }

  void try_step(double t, double& energy, double& total) {
    U_try_.noalias() = U_ + t * d_;
    J_try_.noalias() = J_ + t * dJ_;
    total = evaluate(U_try_, J_try_, R_try_, energy);
  }

  // energy = E with the rotations fitted into R; returns W = E + barrier.
  double evaluate(const Eigen::MatrixXd& U, const Eigen::MatrixXd& J, Eigen::MatrixXd& R,
                  double& energy) const {
    energy = energy_.fit(U, J, R);
    double total = energy;
    for (Eigen::Index f = 0; f < J.rows(); ++f)
      total += disk_.frames.area(f) * barrier_.value(row_matrix(J, f).determinant());
    return total;
  }

  // rhs = -grad W / 2 = r(R) - M U - grad barrier / 2: per face, grad_J (area_f psi(det J_f)) =
  // area_f psi'(det J_f) cof J_f, and vertex F(f, c) gets -(D_f (.)^T) row c / 2.
  void assemble_rhs() {
    energy_.rhs(R_, rhs_);
    rhs_.noalias() -= energy_.system() * U_;
    if (barrier_.weight == 0) return;
    for (Eigen::Index f = 0; f < disk_.F.rows(); ++f) {
      const Eigen::Matrix2d J = row_matrix(J_, f);
      const double slope = barrier_.slope(J.determinant());
      if (slope == 0) continue;
      Eigen::Matrix2d half_G;
      half_G << J(1, 1), -J(1, 0), -J(0, 1), J(0, 0);
      half_G *= 0.5 * disk_.frames.area(f) * slope;
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
  Energy energy_;
  Barrier barrier_;
  double flip_fraction_;
  param_detail::ConstrainedSystem system_;
  std::optional<detail::AndersonAcceleration> anderson_;
  int accepted_mixings_ = 0;
  Eigen::MatrixXd U_, U_try_, U_before_, d_, rhs_; // #V x 2
  Eigen::MatrixXd J_, J_try_, dJ_, R_, R_try_;     // #F x 4 (R: per face or per vertex), row by row
  double E_ = 0, W_ = 0;                           // E and W of the current map
};

// The elements of a per-vertex energy on the disk, laid flat.
PlanarCells cells_of(const DiskMesh& disk, ParamEnergy energy) {
  if (energy == ParamEnergy::Arap) return planar_cells(disk.V, disk.F, arap_edge_elements(disk.V, disk.F));
  IntrinsicOptions options; // the paper's discretization: no boundary refinement, every cell a vertex
  options.refine_boundary = false;
  options.assemble_B = false;
  options.keep_traces = false;
  return planar_cells(disk.V, disk.F, iarap_elements(disk.V, intrinsic_delaunay(disk.V, disk.F, options)));
}

// Runs the iteration; fills the report's iterations, energies, steps, converged (energies in the scaled
// units: the caller multiplies). Returns the final map.
template <typename Energy>
Eigen::MatrixXd iterate(const DiskMesh& disk, Energy energy, const Eigen::MatrixXd& start,
                        const ParamOptions& options, const UvPins& pins, ParamReport& report) {
  auto phase_start = Clock::now();
  const std::vector<int> pinned = pinned_vertices(disk, options.boundary, pins);
  report.pinned = static_cast<int>(pinned.size());
  Barrier barrier;
  if (!options.allow_flips) {
    barrier.weight = options.barrier_weight.value_or(default_barrier_weight(options.energy));
    barrier.threshold = options.barrier_threshold;
  }
  Iteration<Energy> iteration(
      disk, std::move(energy), pinned, barrier, options.allow_flips ? 0.0 : options.step_fraction,
      options.accelerator == ParamAccelerator::Anderson ? options.anderson_window : 0);
  report.factor_ms = ms_since(phase_start);

  phase_start = Clock::now();
  double current = iteration.start(start);
  report.initial_energy = current;
  for (int k = 0; k < options.max_iterations; ++k) {
    double t = 1;
    const double next = iteration.step(t);
    report.energies.push_back(next);
    report.steps.push_back(t);
    report.iterations = k + 1;
    const bool small_decrease = current - next <= options.tolerance * std::abs(current);
    current = next;
    if (small_decrease) {
      report.converged = true;
      break;
    }
  }
  report.iterate_ms = ms_since(phase_start);
  report.accelerator = options.accelerator;
  report.accepted_mixings = iteration.accepted_mixings();
  return iteration.map();
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
  check_uv_pins(options.pins, disk.V.rows());
  const UvPins pins = scaled_pins(options.pins, s);
  report.check_ms = ms_since(total_start);

  auto phase_start = Clock::now();
  Eigen::MatrixXd UV = starting_map(disk, options, pins, report);
  report.init_ms = ms_since(phase_start);

  report.energy = options.energy;
  if (options.energy == ParamEnergy::Triangle) {
    UV = iterate(disk, TriangleEnergy(disk), UV, options, pins, report);
  } else {
    phase_start = Clock::now();
    PlanarCells cells = cells_of(disk, options.energy);
    report.cells_ms = ms_since(phase_start);
    UV = iterate(disk, CellEnergy(std::move(cells)), UV, options, pins, report);
  }
  report.initial_energy *= s * s;
  for (double& e : report.energies) e *= s * s;

  report.distortion = map_distortion(disk.frames, disk.F, UV);
  report.distortion.energy *= s * s;
  report.distortion.scaled_energy *= s * s;
  result.UV = UV * s;
  report.total_ms = ms_since(total_start);
  return result;
}

} // namespace iarap
