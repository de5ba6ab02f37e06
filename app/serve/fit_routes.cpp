// The fit resource: a target (a point cloud or mesh uploaded to fit the mesh to), its points for drawing,
// and a fit started in the background (fit_runner.h) whose rounds come as frames (GET /api/frame);
// POST /api/cancel stops it.
#include "api_routes.h"
#include "binary_frame.h"
#include "client_names.h"
#include "http_error.h"
#include "http_policy.h"
#include "http_reply.h"
#include "json_input.h"
#include "state_json.h"
#include "uploaded_file.h"

#include "iarap/registration/registration_target.h"

namespace iarap::serve {
namespace {

// The most target points the viewer takes: a registration's closest-point queries and the page's drawing
// stay interactive well past a 3D scan's million points; the upload limit alone would allow ~5M (xyz text).
constexpr Eigen::Index max_target_points = 2'000'000;

FitRequest parse_fit_request(const nlohmann::json& body) {
  require_known_fields(body, {"method", "stages", "rounds_per_stage", "prealign"});
  FitRequest request;
  request.method = parse_arap_method(string_field(body, "method", "iarap"));
  RegistrationOptions& options = request.options;
  options.stages = integer_field(body, "stages", options.stages, 1, 50);
  options.rounds_per_stage = integer_field(body, "rounds_per_stage", options.rounds_per_stage, 1, 200);
  try {
    options.prealignment = parse_prealignment(string_field(body, "prealign", "rigid"));
  } catch (const InputError& e) {
    throw HttpError(400, e.what());
  }
  return request;
}

} // namespace

void add_fit_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session,
                    PrivateTempDir& temp) {
  routes.post("/api/target", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string name = safe_label(req.has_param("name") ? req.get_param_value("name") : "");
    const std::string ext = lower_extension(name);
    if (ext != "xyz" && ext != "ply" && ext != "obj" && ext != "off" && ext != "stl")
      throw HttpError(400,
                      "target name \"" + name +
                          "\" must end in .xyz, .ply, .obj (point clouds: their vertices), .off or .stl");
    session.read([](const Session& s) { return s.mesh_summary(); }); // 409 before reading without a mesh
    auto target = std::make_shared<FitTarget>();
    target->name = name;
    read_uploaded_file(req, name, ext, "target file", config, temp,
                       [&](const std::string& path) { target->target = read_registration_target(path); });
    if (target->target.points.rows() > max_target_points)
      throw HttpError(400, name + ": the target has " + std::to_string(target->target.points.rows()) +
                               " points; this server takes at most " + std::to_string(max_target_points));
    session.change([&](Session& s) { s.load_target(std::move(target)); });
    send_json(res, state_json(config, session));
  });

  // The target's points (float32 #P x 3) and, for a mesh, its faces (uint32 #TF x 3).
  routes.get("/api/target", [&](const httplib::Request&, httplib::Response& res) {
    const std::shared_ptr<const FitTarget> target = session.read([](const Session& s) { return s.target(); });
    if (!target) throw SessionConflict("no fit target loaded; upload a point cloud or mesh to fit first");
    const RegistrationTarget& t = target->target;
    const Eigen::MatrixXi& faces = t.faces;
    std::vector<std::uint32_t> face_indices(static_cast<std::size_t>(faces.size()));
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
      for (int k = 0; k < 3; ++k)
        face_indices[static_cast<std::size_t>(3 * f + k)] = static_cast<std::uint32_t>(faces(f, k));
    BinaryFrame frame;
    frame.add("points", to_float_rows(t.points));
    frame.add("faces", face_indices);
    send_binary(res, frame.encode({{"name", target->name},
                                   {"points", t.points.rows()},
                                   {"faces", faces.rows()},
                                   {"diagonal", t.diagonal}}));
  });

  routes.post("/api/fit", [&](const httplib::Request& req, httplib::Response& res) {
    const FitRequest request = parse_fit_request(json_body(req, config));
    const FitStarted started = session.fits().start(session, request);
    send_json(res, {{"generation", started.generation},
                    {"after", started.after},
                    {"method", arap_method_name(request.method)},
                    {"max_rounds", request.options.stages * request.options.rounds_per_stage}});
  });
}

} // namespace iarap::serve
