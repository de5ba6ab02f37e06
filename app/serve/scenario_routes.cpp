// The scenario resource: the session saved as a file `iarap deform` replays (scenario_files.h), and such
// a file loaded back as the session's constraints.
#include "api_routes.h"
#include "client_names.h"
#include "http_error.h"
#include "http_policy.h"
#include "http_reply.h"
#include "scenario_files.h"
#include "solve_request_json.h"
#include "state_json.h"

namespace iarap::serve {

void add_scenario_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session) {
  // The body is a solve request's method and transform / handle_targets.
  routes.post("/api/scenario", [&](const httplib::Request& req, httplib::Response& res) {
    const SolveRequest request = parse_target_request(json_body(req, config), config.max_iterations);
    const auto [targets, mesh] = session.read([&](const Session& s) {
      return std::make_pair(s.constraint_targets(request.method, request), s.mesh_summary().name);
    });
    const SavedSession saved =
        save_session(targets, request.transform,
                     "saved by iarap serve from " + mesh + ", method " + arap_method_name(request.method));
    const std::string file = file_stem(mesh) + (saved.is_scenario ? "_scenario.json" : "_constraints.txt");
    res.set_header("Content-Disposition", "attachment; filename=\"" + file + "\"");
    send_file(res, saved.text, saved.is_scenario ? "application/json" : "text/plain");
  });

  // A scenario or constraints file (body) for the current mesh; name only labels messages.
  routes.post("/api/scenario/load", [&](const httplib::Request& req, httplib::Response& res) {
    require_raw_file(req);
    if (req.body.size() > config.max_json_bytes)
      throw HttpError(413, "scenario file has " + std::to_string(req.body.size()) + " bytes; the limit is " +
                               byte_limit_text(config.max_json_bytes));
    const std::string name = safe_label(req.has_param("name") ? req.get_param_value("name") : "scenario");
    const MeshSnapshot rest = session.read([](const Session& s) { return s.snapshot(std::nullopt); });
    const LoadedSession loaded = load_session(req.body, name, rest.V, rest.F);
    session.change([&](Session& s) {
      return s.load_constraints(loaded.fixed, loaded.handle, loaded.targets, loaded.soft);
    });
    nlohmann::json answer = state_json(config, session);
    answer["warnings"] = loaded.warnings;
    send_json(res, answer);
  });
}

} // namespace iarap::serve
