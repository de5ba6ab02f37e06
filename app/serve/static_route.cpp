// The web app's files (static_files.h decides which), after every API route: an unknown /api/ path is a
// 404 with a JSON message, never a file lookup.
#include "api_routes.h"
#include "client_names.h"
#include "http_error.h"
#include "http_reply.h"
#include "static_files.h"

namespace iarap::serve {

void add_static_route(httplib::Server& server, const ServeConfig& config) {
  server.Get("/api/.*", [](const httplib::Request& req, httplib::Response&) {
    throw HttpError(404, "no API route " + safe_label(req.path));
  });

  server.Get("/.*", [&config](const httplib::Request& req, httplib::Response& res) {
    const std::optional<StaticFile> file = resolve_static_file(config.app_dir, req.path);
    if (!file) throw HttpError(404, "not found: " + safe_label(req.path));
    res.set_header("Cache-Control", "no-cache");
    res.set_header("X-Content-Type-Options", "nosniff");
    send_file(res, read_file_bytes(file->path), file->content_type);
  });
}

} // namespace iarap::serve
