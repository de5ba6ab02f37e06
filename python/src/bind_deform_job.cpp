// deform_file(mesh, scenario=..., constraints=..., ...): the deformation job of `iarap deform` (the library's
// prepare_deform and solve_deform, iarap/jobs/deform_job.h) from Python, the same numbers for the same files.
#include "bindings.h"
#include "keyword_signature.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/jobs/deform_job.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_forces.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/read_stiffness.h"
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
                                       {"pin_unconstrained_components", "bool", py::bool_(false), true},
                                       {"gravity", "npt.ArrayLike | None", py::none(), true},
                                       {"density", "float", py::float_(1.0), true},
                                       {"forces", "_StrPath | None", py::none(), true},
                                       {"stiffness", "_StrPath | None", py::none(), true}};
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
  d["repair"] = scene.repairs;
  d["warnings"] = scene.check.warnings;
  // The total minimized, as `iarap deform` reports it: E_ARAP + penalty + potential (0 without forces).
  d["energy"] = result.report.arap_energy + result.report.penalty + result.report.potential;
  d["precompute_ms"] = result.precompute_ms;
  d["max_displacement"] = result.max_displacement;
  d["bbox_diagonal"] = scene.check.bbox_diagonal;
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
  const std::string mesh_path = path_text(arguments["mesh"]);
  const std::string scenario_path = scenario.is_none() ? "" : path_text(scenario);
  const std::string constraints_path = constraints.is_none() ? "" : path_text(constraints);
  const std::string forces_path = arguments["forces"].is_none() ? "" : path_text(arguments["forces"]);
  const std::string stiffness_path =
      arguments["stiffness"].is_none() ? "" : path_text(arguments["stiffness"]);
  DeformScene scene;
  DeformResult result;
  {
    py::gil_scoped_release release;
    MeshData mesh = read_mesh(mesh_path);
    const auto n = static_cast<int>(mesh.V.rows());
    DeformConstraints given;
    if (!scenario_path.empty())
      given.scenario = read_scenario(scenario_path);
    else
      given.set = read_constraints(constraints_path, n, static_cast<int>(mesh.F.rows()));
    Eigen::MatrixXd forces = forces_path.empty() ? Eigen::MatrixXd() : read_forces(forces_path, n);
    Eigen::VectorXd stiffness =
        stiffness_path.empty() ? Eigen::VectorXd() : read_stiffness(stiffness_path, n);
    scene = prepare_deform(std::move(mesh), given, prepare, std::move(forces), std::move(stiffness));
    if (!scene.check.usable()) {
      std::string message =
          mesh_path + ": mesh not usable for ARAP" + (prepare.repair ? " after repair:" : ":");
      for (const std::string& error : scene.check.errors) message += "\n  " + error;
      throw TopologyError(message);
    }
    result = solve_deform(scene, options, solve, statics);
  }
  return py::make_tuple(to_numpy(result.U), to_numpy(scene.mesh.F), result_dict(scene, result));
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
over; pin_unconstrained_components. gravity (3,) with density: the statics of m_i g (and of the forces file),
every body held. stiffness: a stiffness file ('index s' lines, `iarap deform --stiffness`). The solve options:
)" + solve_option_docs() +
          R"(The report: ARAP.report's fields (in the file's units) with planar, vertices, faces, constrained, soft,
pinned, repair (what the repair did), warnings, energy (E_ARAP + penalty + potential), precompute_ms, max_displacement, bbox_diagonal.
Raises InputError, TopologyError (a mesh not usable: the checks' messages) and SolverError as the tool's
exit code 1 does.)"));
}

} // namespace iarap::python
