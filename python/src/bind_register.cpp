// register(V, F, target_points, ...): non-rigid ICP of a mesh onto a point cloud or mesh with the ARAP
// energy as the regularizer (iarap/registration/register.h) and its report.
#include "bindings.h"
#include "keyword_signature.h"
#include "numpy_arrays.h"
#include "solve_option_keywords.h"

#include "iarap/core/errors.h"
#include "iarap/registration/register.h"

#include <string>
#include <vector>

namespace iarap::python {
namespace {

KeywordSignature register_signature() {
  const RegistrationOptions defaults;
  std::vector<Parameter> parameters = {
      {"V", "npt.ArrayLike", py::object(), false},
      {"F", "npt.ArrayLike", py::object(), false},
      {"target_points", "npt.ArrayLike", py::object(), false},
      {"target_normals", "npt.ArrayLike | None", py::none(), true},
      {"target_faces", "npt.ArrayLike | None", py::none(), true},
      {"landmarks", "npt.ArrayLike | None", py::none(), true},
      {"landmark_targets", "npt.ArrayLike | None", py::none(), true},
      {"landmark_weight", "float", py::float_(defaults.landmark_weight), true},
      {"method", "str", py::str("iarap"), true},
      {"prealign", "str", py::str("rigid"), true},
      {"stages", "int", py::int_(defaults.stages), true},
      {"rounds", "int", py::int_(defaults.rounds_per_stage), true},
      {"initial_weight", "float", py::float_(defaults.initial_data_weight), true},
      {"final_weight", "float", py::float_(defaults.final_data_weight), true},
      {"point_to_plane", "float", py::float_(defaults.point_to_plane), true},
      {"backward_weight", "float", py::float_(defaults.backward_weight), true},
      {"reject_distance", "float", py::float_(defaults.reject_distance), true},
      {"reject_angle", "float", py::float_(defaults.reject_angle_degrees), true},
      {"normal_neighbours", "int", py::int_(12), true}};
  for (Parameter& p : solve_option_parameters(defaults.solve, 0)) parameters.push_back(std::move(p));
  return KeywordSignature("register", std::move(parameters), "tuple[_FloatArray, dict[str, Any]]");
}

py::dict statistics_dict(const DistanceStatistics& s) {
  py::dict d;
  visit_distance_statistics(s, [&d](const char* name, double value) { d[name] = value; });
  return d;
}

py::dict report_dict(const RegistrationReport& report) {
  py::dict d;
  py::dict prealignment;
  prealignment["R"] = to_numpy(Eigen::MatrixXd(report.prealignment.R));
  prealignment["t"] = to_numpy(Eigen::VectorXd(report.prealignment.t));
  prealignment["s"] = report.prealignment.s;
  prealignment["rounds"] = report.prealign_rounds;
  d["prealignment"] = prealignment;
  py::list rounds;
  for (const RegistrationRound& r : report.rounds) {
    py::dict round;
    visit_registration_round(r, report.target_diagonal,
                             [&round](const char* name, auto value) { round[name] = value; });
    rounds.append(round);
  }
  d["rounds"] = rounds;
  d["initial_distance"] = statistics_dict(report.initial_distance);
  d["final_distance"] = statistics_dict(report.final_distance);
  d["target_diagonal"] = report.target_diagonal;
  d["prealign_ms"] = report.prealign_ms;
  d["precompute_ms"] = report.precompute_ms;
  d["closest_ms"] = report.closest_ms;
  d["factor_ms"] = report.factor_ms;
  d["solve_ms"] = report.solve_ms;
  d["total_ms"] = report.total_ms;
  return d;
}

py::tuple register_py(const BoundArguments& arguments) {
  const Eigen::MatrixXd V = to_points(arguments["V"], "V");
  const Eigen::MatrixXi F = to_faces(arguments["F"], "F", V.rows());
  Eigen::MatrixXd points = to_points(arguments["target_points"], "target_points", false);
  Eigen::MatrixXd normals;
  if (!arguments["target_normals"].is_none())
    normals =
        to_points(arguments["target_normals"], "target_normals", false, points.rows(), "#target_points");
  Eigen::MatrixXi faces;
  if (!arguments["target_faces"].is_none())
    faces = to_faces(arguments["target_faces"], "target_faces", points.rows());
  RegistrationLandmarks landmarks;
  if (arguments["landmarks"].is_none() != arguments["landmark_targets"].is_none())
    throw InputError("landmarks and landmark_targets go together: give both or neither");
  if (!arguments["landmarks"].is_none()) {
    landmarks.vertices = to_indices(arguments["landmarks"], "landmarks", V.rows());
    landmarks.vertex_targets = to_points(arguments["landmark_targets"], "landmark_targets", true,
                                         landmarks.vertices.size(), "#landmarks");
  }
  RegistrationOptions options;
  options.landmark_weight = arguments.as<double>("landmark_weight");
  options.method = parse_arap_method(arguments.as<std::string>("method"));
  options.prealignment = parse_prealignment(arguments.as<std::string>("prealign"));
  options.stages = arguments.as<int>("stages");
  options.rounds_per_stage = arguments.as<int>("rounds");
  options.initial_data_weight = arguments.as<double>("initial_weight");
  options.final_data_weight = arguments.as<double>("final_weight");
  options.point_to_plane = arguments.as<double>("point_to_plane");
  options.backward_weight = arguments.as<double>("backward_weight");
  options.reject_distance = arguments.as<double>("reject_distance");
  options.reject_angle_degrees = arguments.as<double>("reject_angle");
  const int neighbours = arguments.as<int>("normal_neighbours");
  set_solve_options(options.solve, arguments);
  RegistrationResult result;
  {
    py::gil_scoped_release release;
    const RegistrationTarget target = make_registration_target(std::move(points), std::move(normals),
                                                               std::move(faces), "target_points", neighbours);
    result = register_to_target(V, F, target, landmarks, options);
  }
  return py::make_tuple(to_numpy(result.U), report_dict(result.report));
}

} // namespace

void bind_register(py::module_& m) {
  def_with_signature(
      m, register_signature(), &register_py,
      std::string(R"(Non-rigid registration: the mesh (V, F) deformed onto a target, (U (#V, 3), report dict).

Non-rigid ICP with the ARAP energy (method: "iarap", "arap" or "spokes-rims") as the regularizer: a rigid
pre-alignment (prealign: "rigid", "similarity" with scale, or "none") from the landmarks (three or more) or
the centroids refined by rigid ICP, then `stages` stages from stiff to soft (data weight from
initial_weight to final_weight, per vertex and relative to its area), each at most `rounds` ICP rounds.
target_points: (#P, 3). target_normals: (#P, 3), or None: from target_faces (#TF, 3) when given, else by
PCA of the normal_neighbours nearest points. landmarks (#l,) source vertices with landmark_targets (#l, 3),
held softly with landmark_weight. Correspondences both ways (target -> source weighted backward_weight),
rejected beyond reject_distance times the median distance or reject_angle degrees between normals, Welsch
weights on the rest; point_to_plane blends the closest point (0) and its tangent plane (1).
Each round's warm-started solve takes the options of ARAP.solve (8 iterations here):
)" + solve_option_docs() +
                  R"(
The report: prealignment (R, t, s, rounds), rounds (per round: stage, round, data_weight, mean_distance and
median_distance as fractions of the target's bounding-box diagonal, forward_used, backward_used,
solver_iterations, energy, closest_ms, factor_ms, solve_ms), initial_distance and final_distance (mean,
median, p90, max: the vertices' distances to the target over its diagonal), target_diagonal, prealign_ms,
precompute_ms, closest_ms, factor_ms, solve_ms, total_ms.
Raises InputError for bad arrays or options (an empty or non-finite target, too few points for normals,
landmarks out of range), TopologyError and SolverError as ARAP does.)"));
}

} // namespace iarap::python
