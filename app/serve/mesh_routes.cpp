// The mesh resource: the session's state, a server mesh or an upload, and what the viewer draws or
// downloads of it (faces, positions, the intrinsic overlay, the deformed mesh as a file).
#include "api_routes.h"
#include "binary_frame.h"
#include "client_names.h"
#include "http_error.h"
#include "http_policy.h"
#include "http_reply.h"
#include "json_input.h"
#include "state_json.h"
#include "uploaded_file.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"

#include <algorithm>

namespace iarap::serve {
namespace {

void add_drawing_routes(RouteTable& routes, SharedSession& session) {
  routes.get("/api/faces", [&](const httplib::Request&, httplib::Response& res) {
    send_binary(res, raw_bytes(session.read([](const Session& s) { return s.faces(); })));
  });

  routes.get("/api/positions", [&](const httplib::Request& req, httplib::Response& res) {
    const bool rest = req.get_param_value("method") == "rest";
    const std::optional<ArapMethod> method =
        rest ? std::nullopt : std::optional<ArapMethod>(method_param(req));
    send_binary(res, raw_bytes(session.read([&](const Session& s) { return s.positions(method); })));
  });

  routes.get("/api/intrinsic_edges", [&](const httplib::Request&, httplib::Response& res) {
    const std::shared_ptr<const IntrinsicOverlay> overlay =
        session.change([](Session& s) { return s.intrinsic_overlay(); });
    BinaryFrame frame;
    frame.add("start", overlay->start);
    frame.add("a", overlay->a);
    frame.add("c", overlay->c);
    frame.add("t", overlay->t);
    frame.add("original", overlay->original);
    send_binary(res, frame.encode({{"edges", overlay->original.size()}, {"points", overlay->a.size()}}));
  });
}

} // namespace

void add_mesh_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session,
                     PrivateTempDir& temp) {
  routes.get("/api/state", [&](const httplib::Request&, httplib::Response& res) {
    send_json(res, state_json(config, session));
  });

  routes.post("/api/load", [&](const httplib::Request& req, httplib::Response& res) {
    const nlohmann::json body = json_body(req, config);
    require_known_fields(body, {"mesh"});
    const std::string name = string_field(body, "mesh", "");
    const auto it = std::find_if(config.meshes.begin(), config.meshes.end(),
                                 [&](const ServerMesh& mesh) { return mesh.name == name; });
    if (it == config.meshes.end())
      throw HttpError(404, "no server mesh named \"" + safe_label(name) + "\"; see meshes in /api/state");
    load_server_mesh(session, *it);
    send_json(res, state_json(config, session));
  });

  routes.post("/api/upload", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string name = safe_label(req.has_param("name") ? req.get_param_value("name") : "");
    const std::string ext = lower_extension(name);
    if (ext != "obj" && ext != "off" && ext != "ply" && ext != "stl" && ext != "mesh" && ext != "msh")
      throw HttpError(400, "upload name \"" + name +
                               "\" must end in .obj, .off, .ply or .stl, or .mesh or .msh (tetrahedra)");
    read_uploaded_file(req, name, ext, "mesh file", config, temp,
                       [&](const std::string& path) { load_mesh_file(session, name, path); });
    send_json(res, state_json(config, session));
  });

  add_drawing_routes(routes, session);

  routes.get("/api/download", [&](const httplib::Request& req, httplib::Response& res) {
    const ArapMethod method = method_param(req);
    const std::string format = req.has_param("format") ? req.get_param_value("format") : "obj";
    if (format != "obj" && format != "off" && format != "ply")
      throw HttpError(400, "format must be obj, off or ply, got \"" + safe_label(format) + "\"");
    const MeshSnapshot snapshot = session.read([&](const Session& s) { return s.snapshot(method); });
    ScopedFile file(temp.unique_path("download", format));
    write_mesh(file.path().string(), snapshot.V, snapshot.F);
    res.set_header("Content-Disposition", "attachment; filename=\"" + file_stem(snapshot.name) + "_" +
                                              arap_method_name(method) + "." + format + "\"");
    send_file(res, read_file_bytes(file.path()), format == "ply" ? "application/octet-stream" : "text/plain");
  });
}

} // namespace iarap::serve
