// The constraints resource: the fixed and handle sets and the rigid groups (a new revision, or an earlier one
// back: undo) and the reset of every method to the rest shape.
#include "api_routes.h"
#include "http_policy.h"
#include "http_reply.h"
#include "json_input.h"
#include "state_json.h"

#include <limits>

namespace iarap::serve {

void add_constraint_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session) {
  routes.post("/api/constraints", [&](const httplib::Request& req, httplib::Response& res) {
    const nlohmann::json body = json_body(req, config);
    if (body.contains("revision")) { // undo / redo: an earlier set with its anchors
      require_known_fields(body, {"revision"});
      const int revision = integer_field(body, "revision", 0, 1, std::numeric_limits<int>::max());
      session.change([&](Session& s) { s.restore_constraints(revision); });
    } else {
      require_known_fields(body, {"fixed", "handle", "rigid_groups"});
      const Eigen::VectorXi fixed = integer_array_field(body, "fixed");
      const Eigen::VectorXi handle = integer_array_field(body, "handle");
      const std::vector<Eigen::VectorXi> rigid_groups = integer_array_list_field(body, "rigid_groups");
      session.change([&](Session& s) { s.set_constraints(fixed, handle, rigid_groups); });
    }
    send_json(res, state_json(config, session));
  });

  routes.post("/api/reset", [&](const httplib::Request& req, httplib::Response& res) {
    if (!req.body.empty()) require_known_fields(json_body(req, config), {});
    session.change([](Session& s) { s.reset(); });
    send_json(res, state_json(config, session));
  });
}

} // namespace iarap::serve
