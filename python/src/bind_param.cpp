// parameterize(V, F, ...): the ARAP parameterization of a disk-like mesh (UV map) and its report.
#include "bindings.h"
#include "keyword_signature.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/validate.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/atlas_report_fields.h"
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

// What parameterize's TopologyError adds for a usable mesh that is not a disk: the call that takes it.
std::string atlas_hint(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const MeshReport check = check_mesh(V, F);
  const bool disk = check.components == 1 && check.boundary_loops == 1 && check.genus == 0;
  if (!check.usable() || disk) return "";
  return "\n(iarap.uv_atlas(V, F) cuts any oriented manifold into disk charts and packs them: per-corner "
         "UVs and chart ids)";
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
  try {
    py::gil_scoped_release release;
    result = arap_parameterize(positions, faces, options);
  } catch (const TopologyError& error) {
    throw TopologyError(error.what() + atlas_hint(positions, faces));
  }
  return py::make_tuple(to_numpy(result.UV), report_dict(result.report));
}

// uv_atlas's parameters: the mesh, the charts' flattening, the atlas's own options, then the engine's.
KeywordSignature uv_atlas_signature() {
  const AtlasOptions defaults;
  std::vector<Parameter> parameters = {
      {"V", "npt.ArrayLike", py::object(), false},
      {"F", "npt.ArrayLike", py::object(), false},
      {"energy", "str", py::str("triangle"), true},
      {"allow_flips", "bool", py::bool_(false), true},
      {"texture_size", "int", py::int_(defaults.texture_size), true},
      {"padding", "float", py::float_(defaults.padding), true},
      {"max_angle", "float", py::float_(defaults.max_normal_angle), true},
      {"target_distortion", "float", py::float_(defaults.target_distortion), true},
      {"min_chart_faces", "int", py::int_(defaults.min_chart_faces), true}};
  for (Parameter& p : solve_option_parameters(defaults.param.solve, 0)) parameters.push_back(std::move(p));
  return KeywordSignature("uv_atlas", std::move(parameters),
                          "tuple[_FloatArray, _IndexArray, dict[str, Any]]");
}

py::dict atlas_report_dict(const AtlasReport& report) {
  py::dict d;
  py::list charts;
  for (const AtlasChart& chart : report.charts) {
    py::dict c;
    visit_atlas_chart(chart, [&c](const char* name, const auto& value) { c[name] = value; });
    charts.append(c);
  }
  d["charts"] = charts;
  visit_atlas_report(report, [&d](const char* name, const auto& value) { d[name] = value; });
  return d;
}

py::tuple uv_atlas_py(const BoundArguments& arguments) {
  const Eigen::MatrixXd positions = to_points(arguments["V"], "V");
  const Eigen::MatrixXi faces = to_faces(arguments["F"], "F", positions.rows());
  AtlasOptions options;
  options.param.energy = parse_param_energy(arguments.as<std::string>("energy"));
  options.param.allow_flips = arguments.as<bool>("allow_flips");
  options.texture_size = arguments.as<int>("texture_size");
  options.padding = arguments.as<double>("padding");
  options.max_normal_angle = arguments.as<double>("max_angle");
  options.target_distortion = arguments.as<double>("target_distortion");
  options.min_chart_faces = arguments.as<int>("min_chart_faces");
  set_solve_options(options.param.solve, arguments);
  UvAtlas atlas;
  {
    py::gil_scoped_release release;
    atlas = uv_atlas(positions, faces, options);
  }
  py::array corner_uv = to_numpy(atlas.corner_uv);
  return py::make_tuple(corner_uv.attr("reshape")(faces.rows(), 3, 2), to_numpy(atlas.chart),
                        atlas_report_dict(atlas.report));
}

} // namespace

void bind_param(py::module_& m) {
  def_with_signature(m, uv_atlas_signature(), &uv_atlas_py,
                     R"(A UV atlas of any triangle mesh: (corner_uv (#F, 3, 2), chart (#F,), report dict).

V: (#V, 3) positions. F: (#F, 3) faces of an oriented manifold (closed or not, any genus, any number of
pieces). The faces are grown into charts that are topological disks within a normal cone of max_angle
degrees, each flattened flip-free as parameterize does (energy, allow_flips and the engine's options, 100
iterations and tolerance 1e-4 here), split where its UV boundary crosses itself or its energy / area exceeds
target_distortion (no part below min_chart_faces), and packed into [0,1]^2 at least padding texels apart
for a texture of texture_size texels (docs/param.md, "Atlas"). corner_uv[f, k] is the UV of corner k of face
f; chart[f] its chart (-1 for a face without an area, whose corners share one UV point).
The report: charts (per chart faces, vertices, area, energy, distortion = energy / area, flipped,
iterations), seam_length, flipped, degenerate_faces, boundary_overlaps, overlap_ratio (rasterized),
energy, area, distortion (energy / area), packing_efficiency (UV area / unit square),
merged_small_charts, splits_for_distortion, splits_for_overlap, segment_ms, flatten_ms, pack_ms,
parameterize_ms.
A disk is cut into charts too; parameterize flattens a disk as one chart (one UV per vertex).
Raises InputError for bad arrays or options, TopologyError for a mesh that is not an oriented manifold.)");

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
components, boundary loops, genus, and naming uv_atlas, which cuts any oriented manifold into an atlas of
charts: per-corner UVs and chart ids) or has degenerate triangles.)"));
}

} // namespace iarap::python
