#include "api_routes.h"

#include "http_policy.h"

#include "iarap/io/read_mesh.h"

namespace iarap::serve {

void load_server_mesh(SharedSession& session, const ServerMesh& mesh) {
  MeshData data = read_mesh(mesh.path);
  session.change([&](Session& s) { s.load_mesh(mesh.name, std::move(data)); });
}

void register_routes(httplib::Server& server, const ServeConfig& config, SharedSession& session,
                     PrivateTempDir& temp) {
  configure_server(server, config);
  RouteTable routes(server);
  add_mesh_routes(routes, config, session, temp);
  add_constraint_routes(routes, config, session);
  add_solve_routes(routes, config, session);
  add_frame_route(routes, session);
  add_scenario_routes(routes, config, session);
  add_param_route(routes, config, session);
  add_fit_routes(routes, config, session, temp);
  routes.answer_other_methods_with_405();
  add_static_route(server, config);
}

} // namespace iarap::serve
