#include "local_global_loops.h"

#include "iarap/core/errors.h"

#include "anderson_acceleration.h"
#include "lbfgs_direction.h"

#include <cmath>
#include <string>

namespace iarap::detail {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Records each accepted iterate in the report and applies the stopping rules.
class Progress {
public:
  Progress(const ArapSolveOptions& options, ArapReport& report, FactorizationKind factorization,
           Clock::time_point start)
      : options_(options), report_(report), factorization_(factorization), start_(start) {}

  // The initial guess. Returns true when the gradient rule already holds (a zero gradient).
  bool begin(double energy, double gradient_norm, double local_ms, double global_ms) {
    report_.initial_energy = energy;
    report_.initial_gradient_norm = gradient_norm;
    report_.local_ms += local_ms;
    report_.global_ms += global_ms;
    if (!std::isfinite(energy))
      throw SolverError("ARAP: the energy of the initial guess is not finite");
    previous_ = energy;
    report_.converged = options_.gradient_tolerance > 0 && gradient_norm == 0.0;
    return report_.converged;
  }

  // Iterate k + 1. Returns true when the solve is to stop.
  bool record(double energy, double gradient_norm, bool accelerated, double local_ms, double global_ms) {
    report_.iterations += 1;
    report_.energies.push_back(energy);
    report_.gradient_norms.push_back(gradient_norm);
    report_.accepted.push_back(accelerated ? 1 : 0);
    report_.local_ms += local_ms;
    report_.global_ms += global_ms;
    report_.local_ms_per_iteration.push_back(local_ms);
    report_.global_ms_per_iteration.push_back(global_ms);
    report_.elapsed_ms.push_back(ms_since(start_));
    if (!std::isfinite(energy))
      throw SolverError("ARAP: the energy became non-finite at iteration " + std::to_string(report_.iterations) +
                        " (factorization " + factorization_name(factorization_) + ")");
    const double previous = previous_;
    previous_ = energy;
    const bool energy_rule = options_.tolerance >= 0 &&
                             (energy == 0.0 || previous - energy <= options_.tolerance * std::abs(previous));
    const bool gradient_rule = options_.gradient_tolerance > 0 &&
                               gradient_norm <= options_.gradient_tolerance * report_.initial_gradient_norm;
    if (energy_rule || gradient_rule) {
      report_.converged = true;
      return true;
    }
    return options_.on_iteration && !options_.on_iteration(report_);
  }

private:
  const ArapSolveOptions& options_;
  ArapReport& report_;
  FactorizationKind factorization_;
  Clock::time_point start_;
  double previous_ = 0;
};

// The global step's tail shared by all loops: rhs at the new iterate and the gradient there.
double rhs_and_gradient_norm(LocalGlobalProblem& problem) {
  problem.assemble_rhs();
  return problem.gradient().norm();
}

void run_plain(LocalGlobalProblem& problem, const ArapSolveOptions& options, Progress& progress) {
  for (int k = 0; k < options.max_iterations; ++k) {
    auto start = Clock::now();
    problem.set_positions(problem.plain_step());
    double global_ms = ms_since(start);
    start = Clock::now();
    const double energy = problem.local_step();
    const double local_ms = ms_since(start);
    start = Clock::now();
    const double gradient_norm = rhs_and_gradient_norm(problem);
    global_ms += ms_since(start);
    if (progress.record(energy, gradient_norm, false, local_ms, global_ms)) return;
  }
}

// Peng et al. 2018, Algorithm 2: the accelerated iterate is kept only when its energy is not above the last
// accepted one; otherwise the plain iterate G(x_k) (whose energy is not above it either, by block descent)
// replaces it and the history restarts from there.
void run_anderson(LocalGlobalProblem& problem, const ArapSolveOptions& options, double energy,
                  ArapReport& report, Progress& progress) {
  AndersonAcceleration anderson(options.window, problem.free_count() * 3);
  Eigen::MatrixXd x = problem.positions(), next(problem.free_count(), 3);
  for (int k = 0; k < options.max_iterations; ++k) {
    auto start = Clock::now();
    Eigen::MatrixXd G = problem.plain_step();
    double global_ms = ms_since(start);
    start = Clock::now();
    const bool combined = anderson.step(x.data(), G.data(), next.data());
    report.accelerator_ms += ms_since(start);
    double local_ms = 0, trial = 0;
    bool accepted = false;
    if (combined) {
      start = Clock::now();
      problem.set_positions(next);
      trial = problem.local_step();
      local_ms += ms_since(start);
      accepted = trial <= energy; // false for NaN as well
      if (accepted) {
        x.swap(next);
      } else {
        ++report.rejected;
        anderson.reset();
      }
    }
    if (!accepted) {
      start = Clock::now();
      x = std::move(G);
      problem.set_positions(x);
      trial = problem.local_step();
      local_ms += ms_since(start);
    }
    energy = trial;
    start = Clock::now();
    const double gradient_norm = rhs_and_gradient_norm(problem);
    global_ms += ms_since(start);
    if (progress.record(energy, gradient_norm, accepted, local_ms, global_ms)) return;
  }
}

// Liu, Bouaziz and Kavan 2017: quasi-Newton on E(x) = min_R energy with H_0 = L_ff^{-1}. The energy is not
// convex, so each step is checked by Armijo backtracking; when that fails, the plain local/global step
// (with no history the L-BFGS step itself) is taken and the history restarts.
void run_lbfgs(LocalGlobalProblem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
               ArapReport& report, Progress& progress) {
  constexpr double kArmijo = 1e-4; // sufficient-decrease constant c_1 (Nocedal & Wright's usual value)
  // Trial lengths 1, 1/2, 1/4 before the fallback: a quasi-Newton step that needs more halving has a poor
  // curvature model, and the plain step costs no more than one more trial.
  constexpr int kTrials = 3;
  LbfgsDirection lbfgs(options.window);
  Eigen::MatrixXd x = problem.positions();
  for (int k = 0; k < options.max_iterations; ++k) {
    auto start = Clock::now();
    Eigen::MatrixXd d = lbfgs.direction(g, problem);
    double slope = inner(g, d);
    bool quasi_newton = lbfgs.pairs() > 0;
    if (quasi_newton && !(slope < 0)) { // not a descent direction: start over with -L_ff^{-1} g
      lbfgs.reset();
      d = -problem.solve(g);
      slope = inner(g, d);
      quasi_newton = false;
    }
    report.accelerator_ms += ms_since(start);
    double local_ms = 0, global_ms = 0, trial = 0;
    bool accepted = false;
    Eigen::MatrixXd x_next;
    start = Clock::now();
    for (int t = 0; t < kTrials && !accepted; ++t) {
      const double alpha = std::ldexp(1.0, -t); // 1, 1/2, 1/4
      x_next = x + alpha * d;
      problem.set_positions(x_next);
      trial = problem.local_step();
      accepted = trial <= energy + kArmijo * alpha * slope; // false for NaN as well
    }
    local_ms += ms_since(start);
    if (!accepted) {
      ++report.rejected;
      lbfgs.reset();
      quasi_newton = false;
      start = Clock::now();
      x_next = problem.plain_step(); // the rhs still belongs to x
      global_ms += ms_since(start);
      start = Clock::now();
      problem.set_positions(x_next);
      trial = problem.local_step();
      local_ms += ms_since(start);
    }
    energy = trial;
    start = Clock::now();
    problem.assemble_rhs();
    Eigen::MatrixXd g_next = problem.gradient();
    global_ms += ms_since(start);
    start = Clock::now();
    lbfgs.push(x_next - x, g_next - g);
    x.swap(x_next);
    g.swap(g_next);
    report.accelerator_ms += ms_since(start);
    if (progress.record(energy, g.norm(), quasi_newton && accepted, local_ms, global_ms)) return;
  }
}

} // namespace

ArapReport run_local_global(LocalGlobalProblem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, Clock::time_point start) {
  ArapReport report;
  report.accelerator = options.window == 0 ? ArapAccelerator::None : options.accelerator;
  Progress progress(options, report, factorization, start);
  auto t = Clock::now();
  const double energy = problem.local_step();
  const double local_ms = ms_since(t);
  t = Clock::now();
  problem.assemble_rhs();
  Eigen::MatrixXd g = problem.gradient();
  if (progress.begin(energy, g.norm(), local_ms, ms_since(t)))
    return report;
  switch (report.accelerator) {
  case ArapAccelerator::None:
    run_plain(problem, options, progress);
    break;
  case ArapAccelerator::Anderson:
    run_anderson(problem, options, energy, report, progress);
    break;
  case ArapAccelerator::Lbfgs:
    run_lbfgs(problem, options, energy, std::move(g), report, progress);
    break;
  }
  return report;
}

} // namespace iarap::detail
