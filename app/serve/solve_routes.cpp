// The solve resource: a solve (its answer as a binary frame), its progress and a cancel, both read
// without the session mutex the solve holds.
#include "api_routes.h"
#include "binary_frame.h"
#include "http_policy.h"
#include "http_reply.h"
#include "solve_request_json.h"

namespace iarap::serve {
namespace {

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
                       {"refinement_iterations_waited", result.refinement_iterations_waited},
                       {"precompute_ms", result.precompute_ms},
                       {"solve_ms", result.solve_ms},
                       {"local_ms", report.local_ms},
                       {"global_ms", report.global_ms},
                       {"pinned", result.pinned},
                       {"planar", result.planar},
                       {"cancelled", result.cancelled},
                       {"generation", result.generation},
                       {"sequence", result.sequence},
                       {"refining", result.refining},
                       {"extrapolation", result.extrapolation},
                       {"vertices", result.positions.size() / 3}});
}

} // namespace

void add_solve_routes(RouteTable& routes, const ServeConfig& config, SharedSession& session) {
  routes.post("/api/solve", [&](const httplib::Request& req, httplib::Response& res) {
    const SolveRequest request = parse_solve_request(json_body(req, config), config.max_iterations);
    const SolveResult result = session.solve(request);
    send_binary(res, solve_frame(request, result));
  });

  // Read while a solve runs (no session mutex): how far it is, and a way to stop it.
  routes.get("/api/progress", [&](const httplib::Request&, httplib::Response& res) {
    SolveProgress& p = session.progress();
    send_json(res, {{"running", p.running.load()},
                    {"method", arap_method_name(static_cast<ArapMethod>(p.method.load()))},
                    {"iteration", p.iteration.load()},
                    {"iterations", p.iterations.load()},
                    {"energy", p.energy.load()}});
  });

  routes.post("/api/cancel", [&](const httplib::Request&, httplib::Response& res) {
    SolveProgress& p = session.progress();
    const bool running = p.running.load();
    if (running) p.cancel_requested = true;
    const bool refining = session.stop_refinement();
    const bool fitting = session.fits().cancel();
    send_json(res, {{"cancelling", running}, {"refinement_stopped", refining}, {"fit_cancelled", fitting}});
  });
}

} // namespace iarap::serve
