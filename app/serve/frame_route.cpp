// The frames resource: GET /api/frame, the newest frame after sequence `after` (a solve's answer or the
// background refinement's), waiting at most wait_ms for one (long polling); 204 when none came. It reads
// the FrameBoard, never the session mutex, so it answers while the refinement runs.
#include "api_routes.h"
#include "binary_frame.h"
#include "http_policy.h"
#include "http_reply.h"

#include <limits>

namespace iarap::serve {
namespace {

// The longest GET /api/frame waits: long enough to span a refinement chunk many times, short enough that
// a client gone away does not hold a worker for long.
constexpr long long max_frame_wait_ms = 10000;

std::string session_frame(const SessionFrame& frame) {
  BinaryFrame body;
  body.add("positions", frame.positions);
  nlohmann::json header = {{"sequence", frame.sequence},
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
  if (frame.fit) {
    const FitFrame& fit = *frame.fit;
    header["fit"] = {{"round", fit.round},           {"stage", fit.stage},
                     {"max_rounds", fit.max_rounds}, {"residual", fit.residual},
                     {"running", fit.running},       {"initial_mean", fit.initial_mean},
                     {"final_mean", fit.final_mean}, {"final_p90", fit.final_p90},
                     {"cancelled", fit.cancelled},   {"committed", fit.committed}};
  }
  return body.encode(header);
}

} // namespace

void add_frame_route(RouteTable& routes, SharedSession& session) {
  routes.get("/api/frame", [&](const httplib::Request& req, httplib::Response& res) {
    const auto after = integer_param(req, "after", 0, 0, std::numeric_limits<long long>::max());
    const auto wait_ms = integer_param(req, "wait_ms", 0, 0, max_frame_wait_ms);
    const std::shared_ptr<const SessionFrame> frame =
        session.frames().wait_newer(static_cast<std::uint64_t>(after), std::chrono::milliseconds(wait_ms));
    if (!frame) {
      res.status = 204;
      return;
    }
    send_binary(res, session_frame(*frame));
  });
}

} // namespace iarap::serve
