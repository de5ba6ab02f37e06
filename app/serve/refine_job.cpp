#include "refine_job.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iarap::serve {
namespace {

// The share of the tolerance that the refinement's gap estimate must reach. The estimate extrapolates the
// last decreases; measured against the energy of an independent solve to a 1e-9 relative gradient (the drag
// bench, beetle and armadillo, Newton), refinements that estimated a gap of 1e-6 had 1.1e-6 to 2.3e-6 left
// (the iterates' rate slows near the end: the trust region, the CG forcing term). Held to a quarter of the
// tolerance, the next runs ended 2.3e-7 (beetle) and 1.5e-9 (armadillo) above their minimum.
constexpr double refinement_aim = 0.25;

// A relative decrease this small is the rounding of the energy's sum, not progress: Newton's steps at the
// minimum are accepted at that level (its trust region raises both decreases by the same 100 eps |E|,
// newton_trust_region.cpp) and their decreases then wander between -5e-16 and +5e-16 without shrinking
// (the bunny's spokes-rims refinement), so a rate read from them says nothing; without this floor only a
// draw at or below zero would end the rule there.
constexpr double rounding_decrease = 100 * std::numeric_limits<double>::epsilon();

} // namespace

double last_relative_decrease(const ArapReport& report) {
  if (report.energies.empty()) return 0;
  const double previous =
      report.energies.size() > 1 ? report.energies[report.energies.size() - 2] : report.initial_energy;
  return previous != 0 ? (previous - report.energies.back()) / std::abs(previous) : 0;
}

double last_energy(const ArapReport& report) {
  return report.energies.empty() ? report.initial_energy : report.energies.back();
}

std::vector<float> to_float_rows(const Eigen::MatrixXd& X) {
  std::vector<float> out(static_cast<std::size_t>(X.rows() * X.cols()));
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index k = 0; k < X.cols(); ++k)
      out[static_cast<std::size_t>(i * X.cols() + k)] = static_cast<float>(X(i, k));
  return out;
}

bool refinement_converged(const std::array<double, 2>& earlier, double decrease, double tolerance) {
  if (decrease <= rounding_decrease) return true;
  if (decrease > tolerance || !(earlier[1] > 0)) return false;
  double rate = decrease / earlier[1];
  if (earlier[0] > 0) rate = std::max(rate, earlier[1] / earlier[0]);
  return rate < 1 && decrease * rate / (1 - rate) <= tolerance;
}

RefineJob refine_job_after(const SolveRequest& request, const ArapReport& report, Eigen::MatrixXd targets,
                           Eigen::MatrixXd soft_targets, Eigen::MatrixXd forces) {
  RefineJob job;
  job.method = request.method;
  job.targets = std::move(targets);
  job.soft_targets = std::move(soft_targets);
  job.options.forces = std::move(forces);
  job.options.max_iterations = request.refine_iterations;
  job.options.tolerance = -1; // the job's own rules, in refine_chunk
  job.options.accelerator = request.refine_accelerator;
  job.options.window = request.solve.window;
  job.options.rotation_smoothing = request.solve.rotation_smoothing; // refines the energy the solve minimized
  job.tolerance = request.solve.tolerance;
  job.gradient_target = request.solve.gradient_tolerance * report.initial_gradient_norm;
  if (request.refine_accelerator == request.solve.accelerator) { // the state goes on (same targets)
    job.trust_radius = report.newton_trust_radius;
    job.reference_gradient = report.newton_reference_gradient;
    job.history = report.accelerator_history;
  }
  job.gradient_now =
      report.gradient_norms.empty() ? report.initial_gradient_norm : report.gradient_norms.back();
  return job;
}

SessionFrame refine_chunk(RefineJob& job, ArapData& data, Eigen::MatrixXd& U, double budget_ms,
                          const std::function<bool()>& keep_going,
                          const std::function<void()>& iteration_done) {
  ArapSolveOptions options = job.options;
  options.time_budget_ms = budget_ms;
  options.warm_start_rotations = true; // the chunk goes on from the last one's rotations
  // A request that waits gets the session within about one plain iteration, not a whole Newton iteration.
  options.should_yield = [&keep_going] { return !keep_going(); };
  if (job.gradient_target > 0) options.gradient_tolerance = job.gradient_target / job.gradient_now;
  options.newton_trust_radius = job.trust_radius;
  options.newton_reference_gradient = job.reference_gradient;
  options.accelerator_history = job.history;
  const bool plain = job.options.accelerator == ArapAccelerator::None || job.options.window == 0;
  bool energy_rule = false;
  // The iteration boundary where a caller of the session takes over (or the server stops), and the
  // energy rule on accelerated iterates.
  options.on_iteration = [&](const ArapReport& report) {
    if (iteration_done) iteration_done();
    if (job.tolerance >= 0 && (plain || report.accepted.back() != 0)) {
      const double decrease = last_relative_decrease(report);
      energy_rule = refinement_converged(job.earlier_decreases, decrease, refinement_aim * job.tolerance);
      job.earlier_decreases = {job.earlier_decreases[1], decrease};
    }
    return !energy_rule && keep_going();
  };
  SessionFrame frame;
  frame.method = job.method;
  frame.refined = true;
  frame.tolerance = job.tolerance;
  try {
    Eigen::MatrixXd next = U;
    const ArapReport report = data.soft.size() == 0
                                  ? arap_solve(data, job.targets, next, options)
                                  : arap_solve(data, job.targets, job.soft_targets, next, options);
    U = std::move(next);
    job.iterations_done += report.iterations;
    job.options.max_iterations -= report.iterations;
    if (!report.gradient_norms.empty()) job.gradient_now = report.gradient_norms.back();
    job.trust_radius = report.newton_trust_radius;
    job.reference_gradient = report.newton_reference_gradient;
    job.history = report.accelerator_history;
    frame.energy = last_energy(report);
    frame.relative_decrease = last_relative_decrease(report);
    frame.converged = report.converged || energy_rule;
    frame.refining = !frame.converged && job.options.max_iterations > 0;
  } catch (const std::exception& e) { // the solver's refusal ends the refinement; U stays the last iterate
    frame.error = e.what();
  }
  frame.iterations = job.iterations_done;
  frame.positions = to_float_rows(U);
  return frame;
}

SessionFrame stopped_refinement_frame(const RefineJob& job, const ArapData& data, const Eigen::MatrixXd& U,
                                      const Eigen::MatrixXd& V) {
  SessionFrame frame;
  frame.method = job.method;
  frame.refined = true;
  frame.iterations = job.iterations_done;
  frame.tolerance = job.tolerance;
  frame.energy = arap_energy(data, U);
  if (data.soft.size() > 0) frame.energy += arap_penalty(data, job.soft_targets, U);
  if (job.options.forces.rows() > 0) frame.energy -= (job.options.forces.array() * (U - V).array()).sum();
  frame.positions = to_float_rows(U);
  return frame;
}

} // namespace iarap::serve
