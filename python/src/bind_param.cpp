// parameterize(V, F, ...): the ARAP parameterization of a disk-like mesh (UV map) and its report.
#include "bindings.h"
#include "numpy_arrays.h"

#include "iarap/core/errors.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/param_report_fields.h"

#include <string>
#include <type_traits>

namespace iarap::python {
namespace {

py::dict report_dict(const ParamReport& report) {
  py::dict d;
  visit_param_report(report, [&d](const char* name, const auto& value) {
    using Value = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<Value, DistortionRange>) {
      py::dict range;
      range["min"] = value.min;
      range["median"] = value.median;
      range["max"] = value.max;
      d[name] = range;
    } else if constexpr (std::is_same_v<Value, std::vector<double>>) {
      d[name] = to_numpy(value);
    } else {
      d[name] = value;
    }
  });
  return d;
}

py::tuple parameterize_py(const py::object& V, const py::object& F, const std::string& energy,
                          const py::object& init, const std::string& boundary, bool allow_flips,
                          int iterations, double tolerance, const py::object& pins, const py::object& pin_uv,
                          const std::string& accelerator, int window, double gradient_tolerance,
                          double time_budget_ms) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  ParamOptions options;
  if (pins.is_none() != pin_uv.is_none())
    throw InputError("pins and pin_uv go together: give both or neither");
  if (!pins.is_none()) {
    options.pins.vertices = to_indices(pins, "pins", positions.rows());
    options.pins.uv = to_points(pin_uv, "pin_uv", true, options.pins.size(), "#pins", true);
    if (options.pins.uv.cols() != 2)
      throw InputError("pin_uv must be (#pins, 2) UV positions; got " +
                       std::to_string(options.pins.uv.cols()) + " columns");
  }
  options.energy = parse_param_energy(energy);
  options.boundary = parse_param_boundary(boundary);
  options.init =
      init.is_none() ? default_param_init(options.boundary) : parse_param_init(init.cast<std::string>());
  options.allow_flips = allow_flips;
  options.solve.accelerator = parse_arap_accelerator(accelerator);
  options.solve.max_iterations = iterations;
  options.solve.tolerance = tolerance;
  options.solve.window = window;
  options.solve.gradient_tolerance = gradient_tolerance;
  options.solve.time_budget_ms = time_budget_ms;
  ParamResult result;
  {
    py::gil_scoped_release release;
    result = arap_parameterize(positions, faces, options);
  }
  return py::make_tuple(to_numpy(result.UV), report_dict(result.report));
}

} // namespace

void bind_param(py::module_& m) {
  m.def("parameterize", &parameterize_py, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("energy") = "triangle", py::arg("init") = py::none(), py::arg("boundary") = "free",
        py::arg("allow_flips") = false, py::arg("iterations") = default_param_solve_options().max_iterations,
        py::arg("tolerance") = default_param_solve_options().tolerance, py::arg("pins") = py::none(),
        py::arg("pin_uv") = py::none(),
        py::arg("accelerator") = arap_accelerator_name(default_param_solve_options().accelerator),
        py::arg("window") = default_param_solve_options().window,
        py::arg("gradient_tolerance") = default_param_solve_options().gradient_tolerance,
        py::arg("time_budget_ms") = default_param_solve_options().time_budget_ms,
        R"(ARAP parameterization (Liu et al. 2008) of a disk-like mesh: (UV (#V, 2), report dict).

V: (#V, 3) positions. F: (#F, 3) faces of a topological disk (one component, one boundary loop, genus 0).
energy: "triangle" (per-triangle rotations, as libigl and CGAL), or per vertex with 2x2 rotations on
flattened cells: "arap" (cotan edges, negative weights kept) or "iarap" (intrinsic Delaunay segments).
init: "lscm" (free boundary), "tutte" or "harmonic" (boundary on a circle of the surface's area); None:
lscm, or harmonic with boundary="circle". boundary: "free" (one vertex pinned) or "circle" (held on that
circle). allow_flips: minimize the energy alone, folds allowed; by default it is flip-free (an injective
start, Tutte's map if the requested one flips, a barrier, and steps that keep every det J > 0).
The solve runs on the engine of ARAP.solve, with the same options: iterations: at most this many;
tolerance: stop when an iteration lowers the energy by at most this fraction of it; accelerator: "newton"
(default), "lbfgs", "anderson" or "none" (the plain iteration), each flip-free unless allow_flips; window:
its history (Newton: CG steps per step); gradient_tolerance: also stop when the gradient norm falls to this
fraction of its initial value (0 = off); time_budget_ms: stop after the iteration that ends past it (0 = off).
pins (#p,) vertex indices with pin_uv (#p, 2): held exactly at those UV positions (mesh units). With the
free boundary they replace the default pin (two or more: the start is LSCM with them held); with
boundary="circle" they must be inner vertices, in the circle's coordinates (centre 0, radius
sqrt(area / pi)). Flip-free, pins that fold the start raise InputError (move them or allow_flips=True).

The report: energy = sum_f area_f ||J_f - R_f||_F^2 of the result whatever energy_kind was minimized
(squared mesh units; initial_energy and energies are the minimized one's, with the barrier when flip-free,
barrier its final value), scaled_energy at the best uniform
scale best_scale, flipped (triangles with det J <= 0), min_det_J (UV area over surface area, signed),
area_distortion and angle_distortion (min / median / max of sigma1 * sigma2 and sigma1 / sigma2),
accelerator, iterations, converged, stop_reason, initial_energy, energies, initial_gradient_norm,
gradient_norms, rejected, solves, elapsed_ms (as ARAP.solve's report), requested_init, init, init_flipped,
init_fallback, pinned, check_ms, init_ms, cells_ms, factor_ms, iterate_ms, parameterize_ms.
Raises InputError for bad arrays or options, TopologyError for a mesh that is not a disk (saying what it has:
components, boundary loops, genus) or has degenerate triangles.)");
}

} // namespace iarap::python
