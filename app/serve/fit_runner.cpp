#include "fit_runner.h"

#include "refine_job.h"
#include "shared_session.h"

namespace iarap::serve {
namespace {

SessionFrame fit_frame(const FitStart& start, ArapMethod method, const Eigen::MatrixXd& U, FitFrame fit) {
  SessionFrame frame;
  frame.generation = start.generation;
  frame.method = method;
  frame.iterations = fit.round;
  frame.refining = fit.running;
  frame.positions = to_float_rows(U);
  frame.fit = fit;
  return frame;
}

} // namespace

FitRunner::~FitRunner() {
  stop();
}

FitStarted FitRunner::start(SharedSession& shared, const FitRequest& request) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (running_.load()) throw SessionConflict("a fit is running; cancel it (POST /api/cancel) before another");
  if (thread_.joinable()) thread_.join(); // the previous fit, finished
  FitStarted started;
  FitStart fit = shared.change([&](Session& s) {
    FitStart begun = s.begin_fit();
    started.after = shared.frames().latest_sequence(); // under the mutex: no frame of the fit yet
    return begun;
  });
  started.generation = fit.generation;
  cancel_ = false;
  running_ = true;
  thread_ = std::thread(
      [this, &shared, fit = std::move(fit), request]() mutable { run(shared, std::move(fit), request); });
  return started;
}

bool FitRunner::cancel() {
  const bool was_running = running_.load();
  cancel_ = true;
  return was_running;
}

void FitRunner::stop() {
  const std::lock_guard<std::mutex> lock(mutex_);
  cancel_ = true;
  if (thread_.joinable()) thread_.join();
}

void FitRunner::run(SharedSession& shared, FitStart start, FitRequest request) {
  RegistrationOptions options = request.options;
  options.method = request.method;
  const double diagonal = start.target->target.diagonal;
  FitFrame progress;
  progress.max_rounds = options.stages * options.rounds_per_stage;
  progress.running = true;
  options.on_round_shape = [&](const RegistrationRound& r, const Eigen::MatrixXd& U) {
    ++progress.round;
    progress.stage = r.stage;
    progress.residual = r.mean_distance / diagonal;
    SessionFrame frame = fit_frame(start, request.method, U, progress);
    frame.energy = r.energy;
    shared.frames().publish(std::move(frame));
    return !cancel_.load() &&
           shared.read([](const Session& s) { return s.generation(); }) == start.generation;
  };
  SessionFrame last;
  try {
    const RegistrationResult result = register_to_target(start.V, start.F, start.target->target, {}, options);
    progress.initial_mean = result.report.initial_distance.mean;
    progress.final_mean = result.report.final_distance.mean;
    progress.final_p90 = result.report.final_distance.p90;
    progress.cancelled = result.report.stopped;
    progress.committed =
        shared.change([&](Session& s) { return s.finish_fit(start.generation, request.method, result.U); });
    last = fit_frame(start, request.method, result.U, progress);
    if (!result.report.rounds.empty()) last.energy = result.report.rounds.back().energy;
  } catch (const std::exception& e) { // the fit's refusal ends it; the session keeps its shape
    last = fit_frame(start, request.method, Eigen::MatrixXd(), progress);
    last.positions = shared.read([&](const Session& s) { return s.positions(request.method); });
    last.error = e.what();
  }
  last.fit->running = false;
  running_ = false; // before the last frame: a client that sees it may start the next fit
  shared.frames().publish(std::move(last));
}

} // namespace iarap::serve
