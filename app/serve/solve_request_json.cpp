#include "solve_request_json.h"

#include "http_error.h"
#include "json_input.h"
#include "solve_option_json.h"

#include <cmath>
#include <string>
#include <vector>

namespace iarap::serve {
namespace {

using nlohmann::json;

ArapAccelerator accelerator_field(const json& body, const char* field, ArapAccelerator fallback) {
  try {
    return parse_arap_accelerator(string_field(body, field, arap_accelerator_name(fallback)));
  } catch (const InputError&) {
    throw HttpError(400, std::string(field) + " must be \"lbfgs\", \"newton\", \"anderson\" or \"none\"");
  }
}

// body[field]: exactly count finite numbers (what they mean, for the message); HttpError 400 otherwise.
std::vector<double> numbers_of_count(const json& body, const char* field, std::size_t count,
                                     const char* meaning) {
  std::vector<double> values = number_array_field(body, field);
  if (values.size() != count)
    throw HttpError(400, std::string(field) + " has " + std::to_string(values.size()) +
                             " numbers; expected " + std::to_string(count) + " (" + meaning + ")");
  return values;
}

// Statics (`iarap deform --gravity --density --forces`): gravity [gx, gy, gz], density > 0, forces 3 x #V
// numbers (their count is checked against the mesh by Session::solve).
void read_statics_fields(const json& body, SolveRequest& request) {
  if (body.contains("gravity")) {
    const std::vector<double> g = numbers_of_count(body, "gravity", 3, "gx, gy, gz in mesh units / time^2");
    request.gravity = Eigen::Vector3d(g[0], g[1], g[2]);
  }
  if (body.contains("density")) {
    const json& density = body.at("density");
    if (!density.is_number() || !std::isfinite(density.get<double>()) || !(density.get<double>() > 0))
      throw HttpError(400, "density must be a finite number > 0 (mass per unit area), got " +
                               short_description(density));
    request.density = density.get<double>();
  }
  if (body.contains("forces")) request.forces = number_array_field(body, "forces");
}

// transform (16 numbers, column-major 4 x 4), handle_targets (x y z per handle vertex) and handle_weights
// (one per handle vertex: a soft handle).
void read_target_fields(const json& body, SolveRequest& request) {
  if (body.contains("transform")) {
    const std::vector<double> m = numbers_of_count(body, "transform", 16, "a column-major 4 x 4 matrix");
    request.transform = Eigen::Map<const Eigen::Matrix4d>(m.data()); // Eigen is column-major too
  }
  if (body.contains("handle_targets")) {
    const std::vector<double> t = number_array_field(body, "handle_targets");
    if (t.size() % 3 != 0)
      throw HttpError(400, "handle_targets has " + std::to_string(t.size()) +
                               " numbers; expected x y z per handle vertex (a multiple of 3)");
    const auto rows = static_cast<Eigen::Index>(t.size() / 3);
    request.handle_targets =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(t.data(), rows, 3);
  }
  if (body.contains(
          "handle_weights")) { // count and sign are checked against the handle (solver_constraints.h)
    const std::vector<double> w = number_array_field(body, "handle_weights");
    request.handle_weights = Eigen::Map<const Eigen::VectorXd>(w.data(), static_cast<Eigen::Index>(w.size()));
  }
}

} // namespace

SolveRequest parse_solve_request(const json& body, int max_iterations) {
  std::vector<std::string> known = solve_option_names();
  known.insert(known.end(), {"method", "transform", "handle_targets", "handle_weights", "cell_energy",
                             "refine", "refine_accelerator", "gravity", "density", "forces", "extrapolate"});
  require_known_fields(body, known);
  SolveRequest request;
  request.method = parse_arap_method(string_field(body, "method", "iarap"));
  read_solve_options(body, request.solve);
  const int iterations = request.solve.max_iterations;
  if (iterations < 1 || iterations > max_iterations)
    throw HttpError(400, "iterations must be an integer in [1, " + std::to_string(max_iterations) +
                             "] on this server (limits.max_iterations); got " + std::to_string(iterations));
  request.cell_energy = bool_field(body, "cell_energy", false);
  request.refine_iterations = bool_field(body, "refine", false) ? max_iterations : 0;
  request.refine_accelerator = accelerator_field(body, "refine_accelerator", request.refine_accelerator);
  request.extrapolate = bool_field(body, "extrapolate", false);
  read_target_fields(body, request);
  read_statics_fields(body, request);
  return request;
}

SolveRequest parse_target_request(const json& body, int max_iterations) {
  require_known_fields(body, {"method", "transform", "handle_targets", "handle_weights"});
  return parse_solve_request(body, max_iterations);
}

} // namespace iarap::serve
