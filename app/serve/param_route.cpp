#include "param_route.h"

#include "../common/param_report_json.h"
#include "api_routes.h"
#include "binary_frame.h"
#include "http_error.h"
#include "http_policy.h"
#include "http_reply.h"
#include "json_input.h"
#include "solve_option_json.h"

#include "iarap/param/arap_parameterize.h"

#include <string>
#include <vector>

namespace iarap::serve {

ParamOptions parse_param_request(const nlohmann::json& body, int max_iterations) {
  std::vector<std::string> known = solve_option_names(); // the engine's options, as POST /api/solve
  known.insert(known.end(), {"energy", "boundary", "init", "allow_flips"});
  require_known_fields(body, known);
  ParamOptions options;
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
  return options;
}

std::string param_frame(const MeshSnapshot& rest, const ParamOptions& options) {
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

// Runs outside the session lock, on a snapshot of the rest mesh.
void add_param_route(RouteTable& routes, const ServeConfig& config, SharedSession& session) {
  routes.post("/api/param", [&](const httplib::Request& req, httplib::Response& res) {
    const ParamOptions options = parse_param_request(json_body(req, config), config.max_iterations);
    const MeshSnapshot rest = session.read([](const Session& s) { return s.snapshot(std::nullopt); });
    send_binary(res, param_frame(rest, options));
  });
}

} // namespace iarap::serve
