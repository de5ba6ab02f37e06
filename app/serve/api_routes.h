// The HTTP routes of `iarap serve`: the JSON / binary API over a ServeState and the static web app.
//
//   GET  /api/state            JSON: mesh summary, server mesh names, fixed / handle indices, constraint
//                              revision, limits, upload formats
//   POST /api/load             {"mesh": NAME}: one of the meshes named on the command line (never a path)
//   POST /api/upload?name=N    body: an OBJ / OFF / PLY / STL file (N only gives the format and a label)
//   GET  /api/faces            uint32 #F x 3;  GET /api/positions?method=M|rest  float32 #V x 3
//   POST /api/constraints      {"fixed": [...], "handle": [...]} (a new revision), or {"revision": R} (undo:
//                              an earlier revision's sets and anchors back)
//   POST /api/solve            {"method", "iterations", "tolerance", "transform" | "handle_targets",
//                               "cell_energy", "refine"} -> binary frame: energies + positions (+ cell
//                               energies); with refine the server keeps solving in the background
//   GET  /api/frame?after=S&wait_ms=T   binary frame: the newest answer or refinement frame numbered
//                              above S, waiting up to T ms (long polling; 204 when none; no session lock)
//   GET  /api/progress         JSON: the running solve's method, iteration, iterations (no session lock)
//   POST /api/cancel           stops the running solve after its current iteration, and the refinement
//   POST /api/reset            every method back to the rest shape
//   POST /api/scenario         {"method", "transform" | "handle_targets"} -> a scenario (JSON) or
//                              constraints file (text) `iarap deform` replays (scenario_files.h)
//   POST /api/scenario/load?name=N   body: such a file; constraints and anchors from it, shapes at rest
//   GET  /api/intrinsic_edges  binary frame: traced intrinsic Delaunay edges (start, a, c, t, original)
//   GET  /api/download?method=M&format=obj|off|ply   the deformed mesh as a file
//   POST /api/param            {"energy", "boundary", "init", "allow_flips", "iterations"} -> binary frame:
//                              the report + "uv" (#V x 2) of the rest mesh's UV map (param_route.h)
// JSON bodies need Content-Type application/json; file bodies any type but a form's. Errors answer
// {"error": message} with 400 (bad request), 403 (foreign Origin / Host), 404, 405 (with Allow), 409 (no
// mesh or no constraints yet, a revision no longer kept), 413 (body over the route's limit), 415 (content
// type) or 422 (mesh or solve the library refuses).
#pragma once
#include "private_temp_dir.h"
#include "serve_state.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace httplib {
class Server;
}

namespace iarap::serve {

struct ServerMesh {
  std::string name; // what clients see and ask for
  std::string path; // known to the server only
};

struct ServeConfig {
  std::filesystem::path app_dir;
  std::vector<ServerMesh> meshes;
  std::size_t max_json_bytes = std::size_t{16} << 20;
  std::size_t max_upload_bytes = std::size_t{64} << 20;
  int max_iterations = 1000;
  // Host header values accepted ("127.0.0.1:8080"...), against DNS rebinding; empty: any.
  std::vector<std::string> allowed_hosts;
  bool verbose = false;
};

// Reads a server mesh into state; throws InputError / TopologyError.
void load_server_mesh(ServeState& state, const ServerMesh& mesh);

// Registers every route and the error handlers. config, state and temp must outlive the server.
void register_routes(httplib::Server& server, const ServeConfig& config, ServeState& state,
                     PrivateTempDir& temp);

} // namespace iarap::serve
