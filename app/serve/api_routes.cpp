#include "api_routes.h"

#include "binary_frame.h"
#include "http_error.h"
#include "json_input.h"
#include "param_route.h"
#include "route_table.h"
#include "scenario_files.h"
#include "solve_option_json.h"
#include "static_files.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

namespace iarap::serve {
namespace {

using nlohmann::json;

// The longest GET /api/frame waits: long enough to span a refinement chunk many times, short enough that
// a client gone away does not hold a worker for long.
constexpr long long max_frame_wait_ms = 10000;

// Invalid UTF-8 (a client's bytes quoted in a parser's message) becomes U+FFFD: a strict dump would throw
// inside the exception handler and end the process.
void send_json(httplib::Response& res, const json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

// Files (the app's scripts, downloads, scenario files) go out as they are. httplib compresses text types
// with brotli at its highest quality whenever the client accepts it: three.core.js (1.4 MB) took 36 s
// on a loaded 2-core machine instead of 1.3 s, and compression buys nothing over loopback. A body given
// by a provider with a known length is sent as is.
void send_file(httplib::Response& res, std::string bytes, const std::string& content_type) {
  const auto body = std::make_shared<const std::string>(std::move(bytes));
  res.set_content_provider(body->size(), content_type,
                           [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                             sink.write(body->data() + offset, std::min(length, body->size() - offset));
                             return true;
                           });
}

void send_binary(httplib::Response& res, const std::string& body) {
  res.set_content(body, "application/octet-stream");
}

template <class T> std::string raw_bytes(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// A client-given name reduced to [A-Za-z0-9._-] (at most 64 characters), for labels and file names.
std::string safe_label(const std::string& name) {
  std::string out;
  for (const char ch : name.substr(0, 64)) {
    const bool ok = std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-';
    out.push_back(ok ? ch : '_');
  }
  return out.empty() ? std::string("mesh") : out;
}

// A mesh name without its extension, safe as a file name.
std::string file_stem(const std::string& name) {
  std::string stem = safe_label(name);
  if (const std::size_t dot = stem.rfind('.'); dot != std::string::npos && dot > 0) stem.resize(dot);
  return stem;
}

std::string lower_extension(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  std::string ext = dot == std::string::npos ? std::string() : name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); !from.empty() && at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read back " + path.filename().string());
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

const char* const json_type_hint = "this route takes a JSON body with Content-Type: application/json "
                                   "(curl: -H 'Content-Type: application/json')";
const char* const raw_file_hint =
    "send the file's bytes as the body with a Content-Type other than a form's, "
    "e.g. curl --data-binary @mesh.off -H 'Content-Type: application/octet-stream'";

bool is_form(const std::string& content_type) {
  return content_type.rfind("application/x-www-form-urlencoded", 0) == 0 ||
         content_type.rfind("multipart/form-data", 0) == 0;
}

// JSON routes take Content-Type application/json, which a form on another web page cannot send without
// a CORS preflight; curl's -d default (a form) is told what to send instead.
void require_json_content(const httplib::Request& req) {
  const std::string type = req.get_header_value("Content-Type");
  if (type.rfind("application/json", 0) != 0) {
    throw HttpError(415, std::string(json_type_hint) + "; got " +
                             (type.empty() ? std::string("none") : "\"" + safe_label(type) + "\""));
  }
}

// File bodies (uploads, saved sessions) are the raw bytes with any Content-Type but a form's: a form
// encodes the bytes, and curl's default -d / --data-binary type is one.
void require_raw_file(const httplib::Request& req) {
  if (is_form(req.get_header_value("Content-Type"))) throw HttpError(415, raw_file_hint);
}

ArapMethod method_param(const httplib::Request& req) {
  return parse_arap_method(req.has_param("method") ? req.get_param_value("method") : "iarap");
}

// The loaded file's soft constraints: the soft vertices with their weights and whether the drag moves them
// (a weighted handle), and the count of points on faces (which keep their targets).
json soft_json(const SoftSession& session) {
  const SoftConstraintSet& soft = session.soft;
  json dragged = json::array();
  for (const char d : session.dragged) dragged.push_back(d != 0);
  return {{"vertices", std::vector<int>(soft.vertices.data(), soft.vertices.data() + soft.vertices.size())},
          {"weights", std::vector<double>(soft.vertex_weights.data(),
                                          soft.vertex_weights.data() + soft.vertex_weights.size())},
          {"dragged", dragged},
          {"face_points", soft.faces.size()},
          {"hard_face_points", soft.hard_faces.size()}};
}

json state_json(const ServeConfig& config, const ServeState& state) {
  json j;
  j["meshes"] = json::array();
  for (const auto& mesh : config.meshes) j["meshes"].push_back(mesh.name);
  j["methods"] = json::array();
  for (const ArapMethod method : all_methods) j["methods"].push_back(arap_method_name(method));
  j["limits"] = {{"max_json_bytes", config.max_json_bytes},
                 {"max_upload_bytes", config.max_upload_bytes},
                 {"max_iterations", config.max_iterations}};
  j["upload_formats"] = {"obj", "off", "ply", "stl"};
  j["mesh"] = nullptr;
  if (state.has_mesh()) {
    const MeshSummary summary = state.mesh_summary();
    j["mesh"] = {{"name", summary.name},   {"vertices", summary.vertices},
                 {"faces", summary.faces}, {"bbox_diagonal", summary.bbox_diagonal},
                 {"notes", summary.notes}, {"warnings", summary.warnings}};
    const Eigen::VectorXi fixed = state.fixed(), handle = state.handle();
    j["fixed"] = std::vector<int>(fixed.data(), fixed.data() + fixed.size());
    j["handle"] = std::vector<int>(handle.data(), handle.data() + handle.size());
    j["soft"] = soft_json(state.soft());
    j["revision"] = state.revision();
  }
  return j;
}

ArapAccelerator accelerator_field(const json& body, const char* field, ArapAccelerator fallback) {
  try {
    return parse_arap_accelerator(string_field(body, field, arap_accelerator_name(fallback)));
  } catch (const InputError&) {
    throw HttpError(400, std::string(field) + " must be \"lbfgs\", \"newton\", \"anderson\" or \"none\"");
  }
}

// Statics (`iarap deform --gravity --density --forces`): gravity [gx, gy, gz], density > 0, forces 3 x #V
// numbers (their count is checked against the mesh by ServeState::solve).
void read_statics_fields(const json& body, SolveRequest& request) {
  if (body.contains("gravity")) {
    const std::vector<double> g = number_array_field(body, "gravity");
    if (g.size() != 3)
      throw HttpError(400, "gravity has " + std::to_string(g.size()) +
                               " numbers; expected 3 (gx, gy, gz in mesh units / time^2)");
    request.gravity = Eigen::Vector3d(g[0], g[1], g[2]);
  }
  if (body.contains("density")) {
    const json& density = body.at("density");
    if (!density.is_number() || !std::isfinite(density.get<double>()) || !(density.get<double>() > 0))
      throw HttpError(400, "density must be a finite number > 0 (mass per unit area), got " +
                               short_description(density));
    request.density = density.get<double>();
  }
  if (body.contains("forces")) request.forces = number_array_field(body, "forces");
}

// The solve options (solve_option_json.h) and the server's own fields. The server holds a request to at
// least one iteration and at most its limit (limits.max_iterations of /api/state), in the schema's words.
SolveRequest parse_solve_request(const json& body, int max_iterations) {
  std::vector<std::string> known = solve_option_names();
  known.insert(known.end(), {"method", "transform", "handle_targets", "cell_energy", "refine",
                             "refine_accelerator", "gravity", "density", "forces"});
  require_known_fields(body, known);
  SolveRequest request;
  request.method = parse_arap_method(string_field(body, "method", "iarap"));
  read_solve_options(body, request.solve);
  const int iterations = request.solve.max_iterations;
  if (iterations < 1 || iterations > max_iterations)
    throw HttpError(400, "iterations must be an integer in [1, " + std::to_string(max_iterations) +
                             "] on this server (limits.max_iterations); got " + std::to_string(iterations));
  request.cell_energy = bool_field(body, "cell_energy", false);
  request.refine_iterations = bool_field(body, "refine", false) ? max_iterations : 0;
  request.refine_accelerator = accelerator_field(body, "refine_accelerator", request.refine_accelerator);
  if (body.contains("transform")) {
    const std::vector<double> m = number_array_field(body, "transform");
    if (m.size() != 16)
      throw HttpError(400, "transform has " + std::to_string(m.size()) +
                               " numbers; expected 16 (a column-major 4 x 4 matrix)");
    request.transform = Eigen::Map<const Eigen::Matrix4d>(m.data()); // Eigen is column-major too
  }
  if (body.contains("handle_targets")) {
    const std::vector<double> t = number_array_field(body, "handle_targets");
    if (t.size() % 3 != 0)
      throw HttpError(400, "handle_targets has " + std::to_string(t.size()) +
                               " numbers; expected x y z per handle vertex (a multiple of 3)");
    const auto rows = static_cast<Eigen::Index>(t.size() / 3);
    request.handle_targets =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(t.data(), rows, 3);
  }
  read_statics_fields(body, request);
  return request;
}

std::string solve_frame(const SolveRequest& request, const SolveResult& result) {
  const ArapReport& report = result.report;
  BinaryFrame frame;
  frame.add("positions", result.positions);
  if (request.cell_energy) frame.add("cell_energy", result.cell_energy);
  return frame.encode({{"method", arap_method_name(request.method)},
                       {"accelerator", arap_accelerator_name(report.accelerator)},
                       {"iterations", report.iterations},
                       {"converged", report.converged},
                       {"stop_reason", arap_stop_reason_name(report.stop_reason)},
                       {"initial_energy", report.initial_energy},
                       {"energies", report.energies},
                       {"arap_energy", report.arap_energy},
                       {"penalty", report.penalty},
                       {"potential", report.potential},
                       {"gradient_norms", report.gradient_norms},
                       {"wait_ms", result.wait_ms},
                       {"refinement_preempted", result.refinement_preempted},
                       {"precompute_ms", result.precompute_ms},
                       {"solve_ms", result.solve_ms},
                       {"local_ms", report.local_ms},
                       {"global_ms", report.global_ms},
                       {"pinned", result.pinned},
                       {"cancelled", result.cancelled},
                       {"generation", result.generation},
                       {"sequence", result.sequence},
                       {"refining", result.refining},
                       {"vertices", result.positions.size() / 3}});
}

std::string session_frame(const SessionFrame& frame) {
  BinaryFrame body;
  body.add("positions", frame.positions);
  json header = {{"sequence", frame.sequence},
                 {"generation", frame.generation},
                 {"method", arap_method_name(frame.method)},
                 {"refined", frame.refined},
                 {"iterations", frame.iterations},
                 {"energy", frame.energy},
                 {"relative_decrease", frame.relative_decrease},
                 {"tolerance", frame.tolerance},
                 {"refining", frame.refining},
                 {"converged", frame.converged},
                 {"vertices", frame.positions.size() / 3}};
  if (!frame.error.empty()) header["error"] = frame.error;
  return body.encode(header);
}

// A whole-number query parameter in [min, max], fallback when absent; 400 naming it otherwise.
long long integer_param(const httplib::Request& req, const char* name, long long fallback, long long min,
                        long long max) {
  if (!req.has_param(name)) return fallback;
  const std::string text = req.get_param_value(name);
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < min || value > max)
    throw HttpError(400, std::string(name) + " must be a whole number from " + std::to_string(min) + " to " +
                             std::to_string(max) + ", got \"" + safe_label(text) + "\"");
  return value;
}

// Messages may quote client data (a parser's last token, a file's line): at most 600 characters go back.
void send_error(httplib::Response& res, std::string message, int status) {
  if (message.size() > 600) message = message.substr(0, 600) + "... (cut)";
  send_json(res, {{"error", message}}, status);
}

// Maps what a handler threw to a status: HttpError its own, InputError 400, Topology/SolverError 422.
void answer_exception(httplib::Response& res, std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const HttpError& e) {
    send_error(res, e.what(), e.status());
  } catch (const InputError& e) {
    send_error(res, e.what(), 400);
  } catch (const TopologyError& e) {
    send_error(res, e.what(), 422);
  } catch (const SolverError& e) {
    send_error(res, e.what(), 422);
  } catch (const std::exception& e) {
    send_error(res, std::string("internal error: ") + e.what(), 500);
  } catch (...) {
    send_error(res, "internal error", 500);
  }
}

// Refuses requests from other web pages (Origin) and from DNS-rebound names (Host).
httplib::Server::HandlerResponse check_origin(const ServeConfig& config, const httplib::Request& req,
                                              httplib::Response& res) {
  const std::string host = req.get_header_value("Host");
  if (!config.allowed_hosts.empty() && std::find(config.allowed_hosts.begin(), config.allowed_hosts.end(),
                                                 host) == config.allowed_hosts.end()) {
    send_json(res, {{"error", "Host \"" + safe_label(host) + "\" is not this server's address"}}, 403);
    return httplib::Server::HandlerResponse::Handled;
  }
  if (req.has_header("Origin") && req.get_header_value("Origin") != "http://" + host) {
    send_json(res, {{"error", "cross-origin requests are refused"}}, 403);
    return httplib::Server::HandlerResponse::Handled;
  }
  return httplib::Server::HandlerResponse::Unhandled;
}

} // namespace

void load_server_mesh(ServeState& state, const ServerMesh& mesh) {
  state.load_mesh(mesh.name, read_mesh(mesh.path));
}

namespace {

// The message of an error status httplib answers itself (no handler ran): 404, 413 with the limit of the
// route, and 415 for a form body httplib refused as too large for a form (8 KiB) when it is within the
// route's limit (curl --data-binary sends a form's type unless told otherwise).
httplib::Server::HandlerResponse answer_transport_error(const ServeConfig& config,
                                                        const httplib::Request& req, httplib::Response& res) {
  if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
  const bool upload = req.path == "/api/upload";
  const std::size_t limit = upload ? config.max_upload_bytes : config.max_json_bytes;
  std::string message = "HTTP " + std::to_string(res.status);
  if (res.status == 404) {
    message = "not found: " + safe_label(req.path);
  } else if (res.status == 400) {
    // httplib refuses a POST without Content-Length (e.g. `curl -X POST URL`) before any route runs.
    message =
        "malformed HTTP request: a " + safe_label(req.method) +
        " needs a Content-Length header (send a body, e.g. curl -d '{}' -H 'Content-Type: application/json')";
  } else if (res.status == 413) {
    const std::string length = req.get_header_value("Content-Length");
    const bool within = !length.empty() && length.size() < 19 &&
                        length.find_first_not_of("0123456789") == std::string::npos &&
                        std::stoull(length) <= limit;
    if (is_form(req.get_header_value("Content-Type")) && within) {
      res.status = 415;
      message = upload || req.path == "/api/scenario/load" ? raw_file_hint : json_type_hint;
    } else {
      message = std::string("request body too large; the limit for ") +
                (upload ? "mesh uploads" : "JSON bodies and scenario files") + " is " +
                byte_limit_text(limit);
    }
  }
  send_error(res, message, res.status);
  return httplib::Server::HandlerResponse::Handled;
}

// The JSON object of a request to a JSON route.
json json_body(const httplib::Request& req, const ServeConfig& config) {
  require_json_content(req);
  return parse_json_object(req.body, config.max_json_bytes);
}

// The part of a solve request that says where the constrained vertices go: method and transform or
// handle_targets.
SolveRequest parse_target_request(const json& body, int max_iterations) {
  require_known_fields(body, {"method", "transform", "handle_targets"});
  return parse_solve_request(body, max_iterations);
}

} // namespace

namespace {

// Status of every failure, the origin check, the transport errors' messages and the optional log.
void configure_server(httplib::Server& server, const ServeConfig& config) {
  server.set_payload_max_length(std::max(config.max_json_bytes, config.max_upload_bytes));
  server.set_pre_routing_handler([&config](const httplib::Request& req, httplib::Response& res) {
    return check_origin(config, req, res);
  });
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
    answer_exception(res, error);
  });
  // Named type: a lambda alone is ambiguous between the two set_error_handler overloads.
  const httplib::Server::HandlerWithResponse error_handler = [&config](const httplib::Request& req,
                                                                       httplib::Response& res) {
    return answer_transport_error(config, req, res);
  };
  server.set_error_handler(error_handler);
  if (config.verbose) {
    server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
      std::cerr << "serve: " << req.method << " " << req.path << " -> " << res.status << "\n";
    });
  }
}

// The session: its state, a server mesh or an upload, the constrained set (with undo) and a reset.
void add_session_routes(RouteTable& routes, const ServeConfig& config, ServeState& state,
                        PrivateTempDir& temp) {
  routes.get("/api/state", [&](const httplib::Request&, httplib::Response& res) {
    send_json(res, state_json(config, state));
  });

  routes.post("/api/load", [&](const httplib::Request& req, httplib::Response& res) {
    const json body = json_body(req, config);
    require_known_fields(body, {"mesh"});
    const std::string name = string_field(body, "mesh", "");
    const auto it = std::find_if(config.meshes.begin(), config.meshes.end(),
                                 [&](const ServerMesh& mesh) { return mesh.name == name; });
    if (it == config.meshes.end())
      throw HttpError(404, "no server mesh named \"" + safe_label(name) + "\"; see meshes in /api/state");
    load_server_mesh(state, *it);
    send_json(res, state_json(config, state));
  });

  routes.post("/api/upload", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string name = safe_label(req.has_param("name") ? req.get_param_value("name") : "");
    const std::string ext = lower_extension(name);
    if (ext != "obj" && ext != "off" && ext != "ply" && ext != "stl")
      throw HttpError(400, "upload name \"" + name + "\" must end in .obj, .off, .ply or .stl");
    require_raw_file(req);
    if (req.body.empty()) throw HttpError(400, "upload body is empty; send the mesh file's bytes");
    if (req.body.size() > config.max_upload_bytes)
      throw HttpError(413, "upload has " + std::to_string(req.body.size()) +
                               " bytes; the limit for file uploads is " +
                               byte_limit_text(config.max_upload_bytes));
    ScopedFile file(temp.unique_path("upload", ext));
    {
      std::ofstream out(file.path(), std::ios::binary);
      out.write(req.body.data(), static_cast<std::streamsize>(req.body.size()));
      if (!out) throw Error("cannot store the upload in the server's temporary folder");
    }
    MeshData mesh;
    try {
      mesh = read_mesh(file.path().string());
    } catch (const InputError& e) { // name the upload, not the server's temporary path
      throw InputError(replace_all(e.what(), file.path().string(), name));
    }
    state.load_mesh(name, std::move(mesh));
    send_json(res, state_json(config, state));
  });

  routes.post("/api/constraints", [&](const httplib::Request& req, httplib::Response& res) {
    const json body = json_body(req, config);
    if (body.contains("revision")) { // undo / redo: an earlier set with its anchors
      require_known_fields(body, {"revision"});
      state.restore_constraints(integer_field(body, "revision", 0, 1, std::numeric_limits<int>::max()));
    } else {
      require_known_fields(body, {"fixed", "handle"});
      state.set_constraints(integer_array_field(body, "fixed"), integer_array_field(body, "handle"));
    }
    send_json(res, state_json(config, state));
  });

  routes.post("/api/reset", [&](const httplib::Request& req, httplib::Response& res) {
    if (!req.body.empty()) require_known_fields(json_body(req, config), {});
    state.reset();
    send_json(res, state_json(config, state));
  });
}

// Solving: a solve, its progress, the frames that follow it (refinement included) and a cancel.
void add_solve_routes(RouteTable& routes, const ServeConfig& config, ServeState& state) {
  routes.post("/api/solve", [&](const httplib::Request& req, httplib::Response& res) {
    const SolveRequest request = parse_solve_request(json_body(req, config), config.max_iterations);
    const SolveResult result = state.solve(request);
    send_binary(res, solve_frame(request, result));
  });

  // Read while a solve runs (no session mutex): how far it is, and a way to stop it.
  routes.get("/api/progress", [&](const httplib::Request&, httplib::Response& res) {
    SolveProgress& p = state.progress();
    send_json(res, {{"running", p.running.load()},
                    {"method", arap_method_name(static_cast<ArapMethod>(p.method.load()))},
                    {"iteration", p.iteration.load()},
                    {"iterations", p.iterations.load()},
                    {"energy", p.energy.load()}});
  });

  // The newest frame after sequence `after` (a solve's answer or the background refinement's), waiting at
  // most wait_ms for one (long polling); 204 when none came. No session mutex.
  routes.get("/api/frame", [&](const httplib::Request& req, httplib::Response& res) {
    const auto after = integer_param(req, "after", 0, 0, std::numeric_limits<long long>::max());
    const auto wait_ms = integer_param(req, "wait_ms", 0, 0, max_frame_wait_ms);
    const std::shared_ptr<const SessionFrame> frame =
        state.frames().wait_newer(static_cast<std::uint64_t>(after), std::chrono::milliseconds(wait_ms));
    if (!frame) {
      res.status = 204;
      return;
    }
    send_binary(res, session_frame(*frame));
  });

  routes.post("/api/cancel", [&](const httplib::Request&, httplib::Response& res) {
    SolveProgress& p = state.progress();
    const bool running = p.running.load();
    if (running) p.cancel_requested = true;
    const bool refining = state.stop_refinement();
    send_json(res, {{"cancelling", running}, {"refinement_stopped", refining}});
  });
}

// What the viewer draws and the files it exchanges: faces, positions, the intrinsic overlay, the UV map,
// scenario files and mesh downloads.
void add_view_routes(RouteTable& routes, const ServeConfig& config, ServeState& state, PrivateTempDir& temp) {
  routes.get("/api/faces", [&](const httplib::Request&, httplib::Response& res) {
    send_binary(res, raw_bytes(state.faces()));
  });

  routes.get("/api/positions", [&](const httplib::Request& req, httplib::Response& res) {
    const bool rest = req.get_param_value("method") == "rest";
    send_binary(
        res, raw_bytes(state.positions(rest ? std::nullopt : std::optional<ArapMethod>(method_param(req)))));
  });

  // The session as a file `iarap deform` replays (see scenario_files.h); the body is a solve request's
  // method and transform / handle_targets.
  routes.post("/api/scenario", [&](const httplib::Request& req, httplib::Response& res) {
    const SolveRequest request = parse_target_request(json_body(req, config), config.max_iterations);
    const ConstraintTargets targets = state.constraint_targets(request.method, request);
    const std::string mesh = state.mesh_summary().name;
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
    const MeshSnapshot rest = state.snapshot(std::nullopt);
    const LoadedSession loaded = load_session(req.body, name, rest.V, rest.F);
    state.load_constraints(loaded.fixed, loaded.handle, loaded.targets, loaded.soft);
    json answer = state_json(config, state);
    answer["warnings"] = loaded.warnings;
    send_json(res, answer);
  });

  routes.get("/api/intrinsic_edges", [&](const httplib::Request&, httplib::Response& res) {
    const std::shared_ptr<const IntrinsicOverlay> overlay = state.intrinsic_overlay();
    BinaryFrame frame;
    frame.add("start", overlay->start);
    frame.add("a", overlay->a);
    frame.add("c", overlay->c);
    frame.add("t", overlay->t);
    frame.add("original", overlay->original);
    send_binary(res, frame.encode({{"edges", overlay->original.size()}, {"points", overlay->a.size()}}));
  });

  // The UV tab: the rest mesh flattened (param_route.h); runs outside the session lock on a snapshot.
  routes.post("/api/param", [&](const httplib::Request& req, httplib::Response& res) {
    const ParamOptions options = parse_param_request(json_body(req, config), config.max_iterations);
    send_binary(res, param_frame(state.snapshot(std::nullopt), options));
  });

  routes.get("/api/download", [&](const httplib::Request& req, httplib::Response& res) {
    const ArapMethod method = method_param(req);
    const std::string format = req.has_param("format") ? req.get_param_value("format") : "obj";
    if (format != "obj" && format != "off" && format != "ply")
      throw HttpError(400, "format must be obj, off or ply, got \"" + safe_label(format) + "\"");
    const MeshSnapshot snapshot = state.snapshot(method);
    ScopedFile file(temp.unique_path("download", format));
    write_mesh(file.path().string(), snapshot.V, snapshot.F);
    res.set_header("Content-Disposition", "attachment; filename=\"" + file_stem(snapshot.name) + "_" +
                                              arap_method_name(method) + "." + format + "\"");
    send_file(res, read_file_bytes(file.path()), format == "ply" ? "application/octet-stream" : "text/plain");
  });
}

} // namespace

void register_routes(httplib::Server& server, const ServeConfig& config, ServeState& state,
                     PrivateTempDir& temp) {
  configure_server(server, config);
  RouteTable routes(server);
  add_session_routes(routes, config, state, temp);
  add_solve_routes(routes, config, state);
  add_view_routes(routes, config, state, temp);
  routes.answer_other_methods_with_405();

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
