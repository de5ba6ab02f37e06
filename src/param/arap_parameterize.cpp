#include "iarap/param/arap_parameterize.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/fixed_boundary_map.h"
#include "iarap/param/lscm.h"
#include "iarap/solver/arap.h"
#include "iarap/solver/solve_option_fields.h"

#include "../solver/local_global_loops.h"
#include "arap_parameterize_disk.h"
#include "injectivity_barrier.h"
#include "uv_elastic_energy.h"
#include "uv_problem.h"

#include <Eigen/LU>
#include <algorithm>
#include <complex>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace iarap {

namespace {

void check_options(const ParamOptions& options) {
  detail::check_solve_options_and_state(options.solve);
  if (options.solve.forces.size() > 0)
    throw InputError("forces do not apply to a UV map: the parameterization has no external forces");
  if (options.solve.rotation_smoothing > 0)
    throw InputError("rotation_smoothing does not apply to a UV map: the parameterization's rotations are "
                     "fitted per triangle, uncoupled; use rotation_smoothing 0");
  if (!(options.step_fraction > 0 && options.step_fraction < 1))
    throw InputError("step_fraction must lie in (0, 1); got " + std::to_string(options.step_fraction));
  if (options.barrier_weight && (!(*options.barrier_weight > 0) || !std::isfinite(*options.barrier_weight)))
    throw InputError("barrier_weight must be a finite number > 0; got " +
                     std::to_string(*options.barrier_weight));
  if (!(options.barrier_threshold > 0) || !std::isfinite(options.barrier_threshold))
    throw InputError("barrier_threshold must be a finite number > 0; got " +
                     std::to_string(options.barrier_threshold));
  if (options.initial_uv.size() > 0) {
    if (options.boundary != ParamBoundary::Free || options.pins.size() > 0)
      throw InputError("a given initial map (initial_uv) needs the free boundary and no pins");
    if (options.initial_uv.cols() != 2 || !options.initial_uv.allFinite())
      throw InputError("initial_uv must be #V x 2 finite UV positions; got " +
                       std::to_string(options.initial_uv.rows()) + " x " +
                       std::to_string(options.initial_uv.cols()));
  }
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

// The caller's initial_uv (in V's units; s the disk's scale) when given and it folds nothing (or folds are
// allowed); else the requested initial map, or Tutte's when the iteration is to stay flip-free and the
// requested one is not injective and Tutte's can hold the pins (not with three or more pins one of which is
// on the boundary, which Tutte's map puts on the circle). Records which one in the report. Throws
// InputError when the flip-free iteration is left with a start the pins fold.
Eigen::MatrixXd starting_map(const DiskMesh& disk, const ParamOptions& options, const UvPins& pins, double s,
                             ParamReport& report) {
  if (options.initial_uv.size() > 0) {
    if (options.initial_uv.rows() != disk.V.rows())
      throw InputError("initial_uv must be #V x 2 = " + std::to_string(disk.V.rows()) + " x 2; got " +
                       std::to_string(options.initial_uv.rows()) + " x 2");
    const Eigen::MatrixXd given = options.initial_uv / s;
    if (options.allow_flips || flipped_triangles(disk, given) == 0) {
      report.requested_init = report.init = options.init;
      report.initial_uv_used = true;
      return given;
    }
  }
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

// Runs the engine on the UV problem from `start`; fills report.solve (scaled units: the caller multiplies),
// the barrier, pinned and the phase times. Returns the final map.
Eigen::MatrixXd iterate(const DiskMesh& disk, const Eigen::MatrixXd& start, const ParamOptions& options,
                        const UvPins& pins, ParamReport& report, Clock::time_point call_start) {
  auto phase_start = Clock::now();
  std::unique_ptr<param_detail::UvElasticEnergy> energy =
      param_detail::make_uv_elastic_energy(disk, options.energy);
  report.cells_ms = ms_since(phase_start);

  phase_start = Clock::now();
  const std::vector<int> pinned = pinned_vertices(disk, options.boundary, pins);
  report.pinned = static_cast<int>(pinned.size());
  std::optional<param_detail::InjectivityBarrier> barrier;
  if (!options.allow_flips)
    barrier.emplace(disk, options.barrier_weight.value_or(default_barrier_weight(options.energy)),
                    options.barrier_threshold, options.step_fraction,
                    face_jacobians(disk.frames, disk.F, start));
  Eigen::MatrixXd UV = start;
  param_detail::UvProblem problem(disk, std::move(energy), pinned, std::move(barrier), UV);
  report.factor_ms = ms_since(phase_start);

  phase_start = Clock::now();
  report.solve = detail::run_local_global(problem, options.solve, problem.factorization(), call_start);
  const double total = problem.local_step(); // the final map's, kept from the loop's last local step
  report.barrier = total - problem.elastic_energy();
  report.iterate_ms = ms_since(phase_start);
  return UV;
}

} // namespace

ParamResult arap_parameterize(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                              const ParamOptions& options) {
  const auto total_start = Clock::now();
  check_options(options);
  // Exact power-of-two scaling: the solve sees coordinates near 1 whatever the units (areas of a mesh at
  // 1e200 would overflow); UV scales back by s, energies by s^2.
  const double s = V.cols() == 3 ? normalizing_scale(V) : 1.0;
  return param_detail::arap_parameterize_disk(prepare_disk(V / s, F), s, options, total_start);
}

namespace param_detail {

ParamResult arap_parameterize_disk(const DiskMesh& disk, double s, const ParamOptions& options,
                                   Clock::time_point total_start) {
  check_options(options);
  ParamResult result;
  ParamReport& report = result.report;
  check_uv_pins(options.pins, disk.V.rows());
  const UvPins pins = scaled_pins(options.pins, s);
  report.check_ms = ms_since(total_start);

  auto phase_start = Clock::now();
  Eigen::MatrixXd UV = starting_map(disk, options, pins, s, report);
  report.init_ms = ms_since(phase_start);

  report.energy = options.energy;
  ParamOptions scaled = options; // lengths in the solve's units, as V / s
  scale_length_options(scaled.solve, s);
  scaled.solve.newton_reference_gradient /= s;
  UV = iterate(disk, UV, scaled, pins, report, total_start);
  rescale_report(report.solve, s);
  report.barrier *= s * s;

  report.distortion = map_distortion(disk.frames, disk.F, UV);
  report.distortion.energy *= s * s;
  report.distortion.scaled_energy *= s * s;
  result.UV = UV * s;
  report.total_ms = ms_since(total_start);
  return result;
}

} // namespace param_detail

} // namespace iarap
