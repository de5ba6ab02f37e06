#include "api_routes.h"

#include "http_policy.h"

#include "iarap/io/read_mesh.h"
#include "iarap/io/read_tet_mesh.h"

namespace iarap::serve {

void load_mesh_file(SharedSession& session, const std::string& name, const std::string& path) {
  if (is_tet_mesh_path(path)) {
    TetMesh tets = read_tet_mesh(path);
    session.change([&](Session& s) { s.load_tet_mesh(name, std::move(tets)); });
    return;
  }
  MeshData data = read_mesh(path);
  session.change([&](Session& s) { s.load_mesh(name, std::move(data)); });
}

void load_server_mesh(SharedSession& session, const ServerMesh& mesh) {
  load_mesh_file(session, mesh.name, mesh.path);
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
