// parameterize(V, F, ...): the ARAP parameterization of a disk-like mesh (UV map) and its report.
#include "bindings.h"
#include "keyword_signature.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/param_report_fields.h"

#include <memory>
#include <string>
#include <type_traits>
#include <vector>

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
    } else {
      d[name] = report_value(value);
    }
  });
  return d;
}

// parameterize's parameters: the mesh, the map's choices, the pins, then the engine's solve options
// (keyword-only, defaults default_param_solve_options(): the names and ranges of ARAP.solve's).
KeywordSignature parameterize_signature() {
  std::vector<Parameter> parameters = {{"V", "npt.ArrayLike", py::object(), false},
                                       {"F", "npt.ArrayLike", py::object(), false},
                                       {"energy", "str", py::str("triangle"), true},
                                       {"init", "str | None", py::none(), true},
                                       {"boundary", "str", py::str("free"), true},
                                       {"allow_flips", "bool", py::bool_(false), true},
                                       {"pins", "npt.ArrayLike | None", py::none(), true},
                                       {"pin_uv", "npt.ArrayLike | None", py::none(), true}};
  for (Parameter& p : solve_option_parameters(default_param_solve_options(), 0))
    parameters.push_back(std::move(p));
  return KeywordSignature("parameterize", std::move(parameters), "tuple[_FloatArray, dict[str, Any]]");
}

UvPins to_pins(const py::object& pins, const py::object& pin_uv, Eigen::Index n) {
  if (pins.is_none() != pin_uv.is_none())
    throw InputError("pins and pin_uv go together: give both or neither");
  UvPins result;
  if (pins.is_none()) return result;
  result.vertices = to_indices(pins, "pins", n);
  result.uv = to_points(pin_uv, "pin_uv", true, result.size(), "#pins", true);
  if (result.uv.cols() != 2)
    throw InputError("pin_uv must be (#pins, 2) UV positions; got " + std::to_string(result.uv.cols()) +
                     " columns");
  return result;
}

py::tuple parameterize_py(const BoundArguments& arguments) {
  const Eigen::MatrixXd positions = to_points(arguments["V"], "V");
  const Eigen::MatrixXi faces = to_faces(arguments["F"], "F", positions.rows());
  ParamOptions options;
  options.energy = parse_param_energy(arguments.as<std::string>("energy"));
  options.boundary = parse_param_boundary(arguments.as<std::string>("boundary"));
  options.init = arguments["init"].is_none() ? default_param_init(options.boundary)
                                             : parse_param_init(arguments.as<std::string>("init"));
  options.allow_flips = arguments.as<bool>("allow_flips");
  options.pins = to_pins(arguments["pins"], arguments["pin_uv"], positions.rows());
  set_solve_options(options.solve, arguments);
  ParamResult result;
  {
    py::gil_scoped_release release;
    result = arap_parameterize(positions, faces, options);
  }
  return py::make_tuple(to_numpy(result.UV), report_dict(result.report));
}

} // namespace

void bind_param(py::module_& m) {
  def_with_signature(
      m, parameterize_signature(), &parameterize_py,
      std::string(R"(ARAP parameterization (Liu et al. 2008) of a disk-like mesh: (UV (#V, 2), report dict).

V: (#V, 3) positions. F: (#F, 3) faces of a topological disk (one component, one boundary loop, genus 0).
energy: "triangle" (per-triangle rotations, as libigl and CGAL), or per vertex with 2x2 rotations on
flattened cells: "arap" (cotan edges, negative weights kept) or "iarap" (intrinsic Delaunay segments).
init: "lscm" (free boundary), "tutte" or "harmonic" (boundary on a circle of the surface's area); None:
lscm, or harmonic with boundary="circle". boundary: "free" (one vertex pinned) or "circle" (held on that
circle). allow_flips: minimize the energy alone, folds allowed; by default it is flip-free (an injective
start, Tutte's map if the requested one flips, a barrier, and steps that keep every det J > 0).
pins (#p,) vertex indices with pin_uv (#p, 2): held exactly at those UV positions (mesh units). With the
free boundary they replace the default pin (two or more: the start is LSCM with them held); with
boundary="circle" they must be inner vertices, in the circle's coordinates (centre 0, radius
sqrt(area / pi)). Flip-free, pins that fold the start raise InputError (move them or allow_flips=True).
The solve runs on the engine of ARAP.solve, with its options (100 iterations here; every accelerator keeps
the map flip-free unless allow_flips):
)" + solve_option_docs() +
                  R"(
The report: energy = sum_f area_f ||J_f - R_f||_F^2 of the result whatever energy_kind was minimized
(squared mesh units; initial_energy and energies are the minimized one's, with the barrier when flip-free,
barrier its final value), scaled_energy at the best uniform
scale best_scale, flipped (triangles with det J <= 0), min_det_J (UV area over surface area, signed),
area_distortion and angle_distortion (min / median / max of sigma1 * sigma2 and sigma1 / sigma2),
accelerator, iterations, converged, stop_reason, initial_energy, energies, initial_gradient_norm,
gradient_norms, rejected, solves, elapsed_ms (as ARAP.solve's report), requested_init, init, init_flipped,
init_fallback, pinned, check_ms, init_ms, cells_ms, factor_ms, iterate_ms, parameterize_ms.
Raises InputError for bad arrays or options, TopologyError for a mesh that is not a disk (saying what it has:
components, boundary loops, genus) or has degenerate triangles.)"));
}

} // namespace iarap::python
