// deform_file(mesh, scenario=..., constraints=..., ...): the deformation job of `iarap deform` (the library's
// prepare_deform and solve_deform, iarap/jobs/deform_job.h) from Python, the same numbers for the same files.
#include "bindings.h"
#include "keyword_signature.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/jobs/deform_job.h"
#include "iarap/jobs/volume_deform.h"
#include "iarap/solver/solve_report_fields.h"

#include <memory>
#include <string>
#include <vector>

namespace iarap::python {
namespace {

// The job's parameters: the files, the method and repair, the statics' forces, then the solve options of
// the schema (keyword-only, the defaults of `iarap deform`).
KeywordSignature deform_file_signature() {
  std::vector<Parameter> parameters = {{"mesh", "_StrPath", py::object(), false},
                                       {"scenario", "_StrPath | None", py::none(), true},
                                       {"constraints", "_StrPath | None", py::none(), true},
                                       {"method", "str", py::str("iarap"), true},
                                       {"refine_boundary", "bool", py::bool_(true), true},
                                       {"repair", "bool", py::bool_(false), true},
                                       {"keep_numbering", "bool", py::bool_(false), true},
                                       {"pin_unconstrained_components", "bool", py::bool_(false), true},
                                       {"gravity", "npt.ArrayLike | None", py::none(), true},
                                       {"density", "float", py::float_(1.0), true},
                                       {"forces", "_StrPath | None", py::none(), true},
                                       {"stiffness", "_StrPath | None", py::none(), true},
                                       {"rigid", "_StrPath | None", py::none(), true},
                                       {"volume", "bool", py::bool_(false), true}};
  for (Parameter& p : solve_option_parameters(ArapSolveOptions{}, 0)) parameters.push_back(std::move(p));
  return KeywordSignature("deform_file", std::move(parameters),
                          "tuple[_FloatArray, _IndexArray, dict[str, Any]]");
}

std::string path_text(const py::object& path) {
  return py::str(py::module_::import("os").attr("fspath")(path));
}

py::dict result_dict(const DeformScene& scene, const DeformResult& result) {
  py::dict d;
  visit_arap_report(result.report,
                    [&d](const char* name, const auto& value) { d[name] = report_value(value); });
  d["planar"] = result.planar;
  d["vertices"] = scene.mesh.V.rows();
  d["faces"] = scene.mesh.F.rows();
  d["constrained"] = scene.constraints.fixed.size();
  d["soft"] = scene.constraints.soft.size();
  d["pinned"] = result.data.pinned.size();
  d["min_weight"] = result.data.min_weight;
  d["tufted_cover"] = result.data.intrinsic.tufted_cover;
  d["repair"] = scene.repairs;
  // A deformable mesh's errors only say that it is not an oriented manifold (deformed as it is).
  std::vector<std::string> warnings = scene.check.warnings;
  warnings.insert(warnings.end(), scene.check.errors.begin(), scene.check.errors.end());
  d["warnings"] = warnings;
  // The total minimized, as `iarap deform` reports it: E_ARAP + penalty + potential (0 without forces).
  d["energy"] = result.report.arap_energy + result.report.penalty + result.report.potential;
  d["precompute_ms"] = result.precompute_ms;
  d["max_displacement"] = result.max_displacement;
  d["bbox_diagonal"] = scene.check.bbox_diagonal;
  if (scene.check.boundary_edges == 0) // a closed surface: the volume it encloses after / before
    d["volume_ratio"] = enclosed_volume(result.U, scene.mesh.F) / enclosed_volume(scene.mesh.V, scene.mesh.F);
  return d;
}

py::tuple deform_file_py(const BoundArguments& arguments) {
  const py::object &scenario = arguments["scenario"], &constraints = arguments["constraints"];
  if (scenario.is_none() == constraints.is_none())
    throw InputError("deform_file needs exactly one of scenario= and constraints= (a file path)");
  ArapOptions options;
  options.method = parse_arap_method(arguments.as<std::string>("method"));
  options.intrinsic.refine_boundary = arguments.as<bool>("refine_boundary");
  options.pin_unconstrained_components = arguments.as<bool>("pin_unconstrained_components");
  ArapSolveOptions solve;
  set_solve_options(solve, arguments);
  StaticForces statics;
  statics.density = arguments.as<double>("density"); // checked by the job (static_forces)
  statics.present = !arguments["gravity"].is_none() || !arguments["forces"].is_none();
  if (!arguments["gravity"].is_none()) statics.gravity = to_vector3(arguments["gravity"], "gravity");
  DeformPrepareOptions prepare;
  prepare.repair = arguments.as<bool>("repair");
  if (arguments.as<bool>("keep_numbering") && !prepare.repair)
    throw InputError("deform_file: keep_numbering=True needs repair=True (without a repair the numbering is "
                     "the file's already)");
  const auto path_or_empty = [&](const char* name) {
    return arguments[name].is_none() ? std::string() : path_text(arguments[name]);
  };
  const DeformFiles files{path_text(arguments["mesh"]), path_or_empty("scenario"),
                          path_or_empty("constraints"), path_or_empty("forces"),
                          path_or_empty("stiffness"),   path_or_empty("rigid")};
  const std::string& mesh_path = files.mesh;
  DeformScene scene;
  DeformResult result;
  {
    py::gil_scoped_release release;
    scene = read_deform_scene(files, prepare);
    if (!scene.check.deformable()) { // not an oriented manifold only: deformed as it is
      std::string message =
          mesh_path + ": mesh not usable for ARAP" + (prepare.repair ? " after repair:" : ":");
      for (const std::string& error : scene.check.errors) message += "\n  " + error;
      throw TopologyError(message);
    }
    if (arguments.as<bool>("volume")) { // the surface's inside tetrahedralized; its result the first rows
      const Eigen::Index n = scene.mesh.V.rows();
      const DeformScene solid = volume_scene(scene);
      result = solve_deform(solid, options, solve, statics);
      result.U.conservativeResize(n, 3);
    } else {
      result = solve_deform(scene, options, solve, statics);
    }
  }
  if (!arguments.as<bool>("keep_numbering"))
    return py::make_tuple(to_numpy(result.U), to_numpy(scene.mesh.F), result_dict(scene, result));
  double spread = 0.0;
  const Eigen::MatrixXd U = in_input_numbering(scene, result.U, &spread);
  py::dict report = result_dict(scene, result);
  report["copies_spread"] = spread;
  return py::make_tuple(to_numpy(U), to_numpy(scene.input.F), report);
}

} // namespace

void bind_deform_job(py::module_& m) {
  def_with_signature(
      m, deform_file_signature(), &deform_file_py,
      std::string(
          R"(The job of `iarap deform MESH --scenario FILE | --constraints FILE`, in the library (prepare_deform,
solve_deform): the same numbers as the tool for the same files and options. Returns (U (#V, 3) float64,
F (#F, 3) of the mesh as solved: repaired when repair=True, else the file's, report dict).

mesh, scenario, constraints, forces: file paths (exactly one of scenario and constraints). method: "iarap",
"arap" or "spokes-rims"; refine_boundary (iARAP only); repair: repair the mesh first, the constraints carried
over; keep_numbering (with repair): U and F in the file's numbering, each vertex at the mean of its copies
(the report's copies_spread: their largest distance from it); pin_unconstrained_components. gravity (3,) with density: the statics of m_i g (and of the forces file),
every body held. stiffness: a stiffness file ('index s' lines, `iarap deform --stiffness`). rigid: a
rigid-groups file (one group per line, `iarap deform --rigid`; every accelerator). volume: deform
the closed surface as a solid (`iarap deform --volume`: TetGen's tetrahedra, the surface's rows returned with
its faces; the report's volume_ratio is the enclosed volume after / before). The solve options:
)" + solve_option_docs() +
          R"(The report: ARAP.report's fields (in the file's units) with planar, vertices, faces, constrained, soft,
pinned, min_weight (the smallest element weight), tufted_cover (iARAP ran on the tufted cover: the mesh is not
an oriented manifold), repair (what the repair did), warnings (with the errors of a mesh that is only not an
oriented manifold), energy (E_ARAP + penalty + potential), precompute_ms, max_displacement, bbox_diagonal,
volume_ratio (a closed surface: the volume it encloses after / before).
Raises InputError, TopologyError (a mesh not usable: the checks' messages) and SolverError as the tool's
exit code 1 does.)"));
}

} // namespace iarap::python
