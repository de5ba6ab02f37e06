#include "param_route.h"

#include "../common/param_report_json.h"
#include "api_routes.h"
#include "binary_frame.h"
#include "http_error.h"
#include "http_policy.h"
#include "http_reply.h"
#include "json_input.h"
#include "solve_option_json.h"

#include "iarap/mesh/validate.h"
#include "iarap/param/arap_parameterize.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace iarap::serve {
namespace {

// A number field that must satisfy `ok`, else 400 naming the field, the range and the value.
double checked_number(const nlohmann::json& body, const char* field, double fallback, bool (*ok)(double),
                      const std::string& range) {
  const double value = number_field(body, field, fallback);
  if (!ok(value))
    throw HttpError(400,
                    std::string(field) + " must be " + range + "; got " + short_description(body.at(field)));
  return value;
}

// The atlas's own fields, by the names of `iarap param`'s options (--texture-size, --max-angle, ...).
void read_atlas_fields(const nlohmann::json& body, AtlasOptions& atlas) {
  atlas.texture_size = integer_field(body, "texture_size", atlas.texture_size, 16, 16384);
  atlas.padding = number_field(body, "padding", atlas.padding);
  if (!(atlas.padding >= 0 && atlas.padding < atlas.texture_size / 2.0))
    throw HttpError(400, "padding must lie in [0, texture_size / 2) = [0, " +
                             std::to_string(atlas.texture_size / 2) + (atlas.texture_size % 2 ? ".5" : "") +
                             ") texels; got " + short_description(body.at("padding")));
  atlas.max_normal_angle = checked_number(
      body, "max_angle", atlas.max_normal_angle, [](double a) { return a > 0 && a <= 180; },
      "in (0, 180] degrees");
  atlas.target_distortion = checked_number(
      body, "target_distortion", atlas.target_distortion, [](double d) { return d > 0; }, "a number > 0");
  atlas.min_chart_faces =
      integer_field(body, "min_chart_faces", atlas.min_chart_faces, 1, std::numeric_limits<int>::max());
}

// As `iarap param --charts auto`: a disk (one component, one boundary loop, genus 0) is one chart; a mesh
// check_mesh cannot use goes to the atlas, which refuses it with check_mesh's words.
bool is_topological_disk(const MeshReport& check) {
  return check.usable() && check.components == 1 && check.boundary_loops == 1 && check.genus == 0;
}

std::string disk_frame(const MeshSnapshot& rest, const ParamOptions& options) {
  const ParamResult result = arap_parameterize(rest.V, rest.F, options);
  std::vector<float> uv(static_cast<std::size_t>(result.UV.size()));
  for (Eigen::Index v = 0; v < result.UV.rows(); ++v)
    for (int k = 0; k < 2; ++k) uv[static_cast<std::size_t>(2 * v + k)] = static_cast<float>(result.UV(v, k));
  BinaryFrame frame;
  frame.add("uv", uv);
  nlohmann::json header = cli::param_report_json(result.report);
  header["mesh"] = rest.name;
  header["vertices"] = result.UV.rows();
  header["boundary"] = param_boundary_name(options.boundary);
  header["allow_flips"] = options.allow_flips;
  return frame.encode(header);
}

// The atlas's report as `iarap param --json` names it (charts, chart_list, the report's fields, the options),
// with the mesh's topology (why it is an atlas).
nlohmann::json atlas_header(const MeshSnapshot& rest, const MeshReport& check, const AtlasOptions& options,
                            const AtlasReport& report) {
  nlohmann::json j;
  j["mesh"] = rest.name;
  j["atlas"] = true;
  j["faces"] = rest.F.rows();
  j["components"] = check.components;
  j["boundary_loops"] = check.boundary_loops;
  j["genus"] = check.genus ? nlohmann::json(*check.genus) : nlohmann::json(nullptr);
  cli::add_atlas_report_json(j, options, report);
  return j;
}

std::string atlas_frame(const MeshSnapshot& rest, const MeshReport& check, const AtlasOptions& options) {
  const UvAtlas atlas = uv_atlas(rest.V, rest.F, options);
  std::vector<float> corner_uv(static_cast<std::size_t>(atlas.corner_uv.size()));
  for (Eigen::Index c = 0; c < atlas.corner_uv.rows(); ++c)
    for (int k = 0; k < 2; ++k)
      corner_uv[static_cast<std::size_t>(2 * c + k)] = static_cast<float>(atlas.corner_uv(c, k));
  BinaryFrame frame;
  frame.add("corner_uv", corner_uv);
  frame.add("chart", std::vector<std::int32_t>(atlas.chart.data(), atlas.chart.data() + atlas.chart.size()));
  return frame.encode(atlas_header(rest, check, options, atlas.report));
}

} // namespace

ParamRequest parse_param_request(const nlohmann::json& body, int max_iterations) {
  std::vector<std::string> known = solve_option_names(); // the engine's options, as POST /api/solve
  known.insert(known.end(), {"energy", "boundary", "init", "allow_flips", "charts", "texture_size", "padding",
                             "max_angle", "target_distortion", "min_chart_faces"});
  require_known_fields(body, known);
  ParamRequest request;
  ParamOptions& options = request.disk;
  options.energy = parse_param_energy(string_field(body, "energy", "triangle"));
  options.boundary = parse_param_boundary(string_field(body, "boundary", "free"));
  const std::string init = string_field(body, "init", "");
  options.init = init.empty() ? default_param_init(options.boundary) : parse_param_init(init);
  options.allow_flips = bool_field(body, "allow_flips", false);
  read_solve_options(body, options.solve);
  if (options.solve.max_iterations > max_iterations)
    throw HttpError(400, "iterations must be an integer in [0, " + std::to_string(max_iterations) +
                             "] on this server (limits.max_iterations); got " +
                             std::to_string(options.solve.max_iterations));
  const std::string charts = string_field(body, "charts", "auto");
  if (charts != "auto" && charts != "one")
    throw HttpError(400, "charts must be auto (a disk is one chart, another mesh an atlas) or one (the mesh "
                         "must be a disk); got \"" +
                             charts + "\" (keep needs an OBJ's vt seams, which the viewer does not load)");
  request.one_chart = charts == "one";
  read_atlas_fields(body, request.atlas);
  request.atlas.param = options;
  if (!body.contains("tolerance"))
    request.atlas.param.solve.tolerance = default_atlas_param_options().solve.tolerance;
  return request;
}

std::string param_frame(const MeshSnapshot& rest, const ParamRequest& request) {
  if (request.one_chart) return disk_frame(rest, request.disk);
  const MeshReport check = check_mesh(rest.V, rest.F);
  if (is_topological_disk(check)) return disk_frame(rest, request.disk);
  return atlas_frame(rest, check, request.atlas);
}

// Runs outside the session lock, on a snapshot of the rest mesh.
void add_param_route(RouteTable& routes, const ServeConfig& config, SharedSession& session) {
  routes.post("/api/param", [&](const httplib::Request& req, httplib::Response& res) {
    const ParamRequest request = parse_param_request(json_body(req, config), config.max_iterations);
    const MeshSnapshot rest = session.read([](const Session& s) { return s.snapshot(std::nullopt); });
    send_binary(res, param_frame(rest, request));
  });
}

} // namespace iarap::serve
