// The HTTP routes of `iarap serve`: the JSON / binary API over a SharedSession and the static web app.
// One file per resource registers its routes (add_*_routes below); http_policy.h holds what every route
// shares (who may call, body types, limits, error statuses).
//
//   GET  /api/state            JSON: mesh summary, server mesh names, fixed / handle indices, constraint
//                              revision, limits, upload formats                               (mesh_routes)
//   POST /api/load             {"mesh": NAME}: one of the meshes named on the command line (never a path)
//   POST /api/upload?name=N    body: an OBJ / OFF / PLY / STL file, or a MEDIT .mesh / gmsh .msh
//                              tetrahedral mesh (N only gives the format and a label)
//   GET  /api/faces            uint32 #F x 3;  GET /api/positions?method=M|rest  float32 #V x 3
//   GET  /api/intrinsic_edges  binary frame: traced intrinsic Delaunay edges (start, a, c, t, original)
//   GET  /api/download?method=M&format=obj|off|ply   the deformed mesh as a file
//   POST /api/constraints      {"fixed": [...], "handle": [...]} (a new revision), or {"revision": R} (undo:
//                              an earlier revision's sets and anchors back)          (constraint_routes)
//   POST /api/reset            every method back to the rest shape
//   POST /api/solve            {"method", "iterations", "tolerance", "transform" | "handle_targets",
//                               "cell_energy", "refine"} -> binary frame: energies + positions (+ cell
//                               energies); with refine the server keeps solving in the background
//                                                                                        (solve_routes)
//   GET  /api/progress         JSON: the running solve's method, iteration, iterations (no session lock)
//   POST /api/cancel           stops the running solve after its current iteration, the refinement and a fit
//   GET  /api/frame?after=S&wait_ms=T   binary frame: the newest answer or refinement frame numbered
//                              above S, waiting up to T ms (long polling; 204 when none; no session lock)
//                                                                                         (frame_route)
//   POST /api/scenario         {"method", "transform" | "handle_targets"} -> a scenario (JSON) or
//                              constraints file (text) `iarap deform` replays (scenario_files.h)
//   POST /api/scenario/load?name=N   body: such a file; constraints and anchors from it, shapes at rest
//                                                                                     (scenario_routes)
//   POST /api/param            {"energy", "boundary", "init", "allow_flips", "iterations"} -> binary frame:
//                              the report + "uv" (#V x 2) of the rest mesh's UV map          (param_route)
//   POST /api/target?name=N    body: a point cloud (.xyz, .ply / .obj vertices) or mesh to fit to
//   GET  /api/target           binary frame: its points (and faces) for drawing
//   POST /api/fit              {"method", "stages", "rounds_per_stage", "prealign"}: registers the rest mesh
//                              to the target in the background; its rounds come as frames   (fit_routes)
//   GET  /...                  the web app's files (static_files.h)                       (static_route)
// JSON bodies need Content-Type application/json; file bodies any type but a form's. Errors answer
// {"error": message} with 400 (bad request), 403 (foreign Origin / Host), 404, 405 (with Allow), 409 (no
// mesh or no constraints yet, a revision no longer kept), 413 (body over the route's limit), 415 (content
// type) or 422 (mesh or solve the library refuses).
#pragma once
// Eigen before httplib: a macro of httplib's system headers breaks Eigen's product kernels otherwise.
#include "shared_session.h"

#include "private_temp_dir.h"
#include "route_table.h"
#include "serve_config.h"

namespace httplib {
class Server;
}

namespace iarap::serve {

// Reads the mesh file at path into the session under name: a tetrahedral mesh by its extension (.mesh .msh
// .node .ele: is_tet_mesh_path), else a triangle mesh. Throws InputError / TopologyError.
void load_mesh_file(SharedSession& session, const std::string& name, const std::string& path);
// The same for a server mesh.
void load_server_mesh(SharedSession& session, const ServerMesh& mesh);

// Registers every route and the error handlers. config, session and temp must outlive the server.
void register_routes(httplib::Server& server, const ServeConfig& config, SharedSession& session,
                     PrivateTempDir& temp);

// The routes of each resource (its own .cpp file), for register_routes.
void add_mesh_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session,
                     PrivateTempDir& temp);
void add_constraint_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session);
void add_solve_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session);
void add_frame_route(RouteTable& routes, SharedSession& session);
void add_scenario_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session);
void add_param_route(RouteTable& routes, const ServeConfig& config, SharedSession& session);
void add_fit_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session,
                    PrivateTempDir& temp);
// After every other route: GET /api/... answers 404, any other GET a file of config.app_dir.
void add_static_route(httplib::Server& server, const ServeConfig& config);

} // namespace iarap::serve
