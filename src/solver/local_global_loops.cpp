#include "local_global_loops.h"

#include "iarap/core/errors.h"

#include "anderson_acceleration.h"
#include "lbfgs_direction.h"

#include <algorithm>
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
    if (!std::isfinite(energy)) throw SolverError("ARAP: the energy of the initial guess is not finite");
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
      throw SolverError("ARAP: the energy became non-finite at iteration " +
                        std::to_string(report_.iterations) + " (factorization " +
                        factorization_name(factorization_) + ")");
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

// Where a step along a descent direction d (slope = g . d < 0) from x ends: Armijo backtracking with lengths
// 1, 1/2, 1/4 (a quasi-Newton or Newton step that needs more halving has a poor curvature model, and the
// plain step costs no more than one more trial); when none passes, or d is not a descent direction, the plain
// local/global step (the rhs still belongs to x). The local step at the returned point is done.
struct LineStep {
  Eigen::MatrixXd x;
  double energy = 0;
  bool accepted = false; // false: the plain step
  double local_ms = 0, global_ms = 0;
};

// Replaces a rejected trial by the plain local/global step from x (the rhs is still the one assembled at x);
// the trial's time stays in the step's.
void take_plain_step(LocalGlobalProblem& problem, LineStep& step) {
  auto start = Clock::now();
  step.x = problem.plain_step();
  step.global_ms += ms_since(start);
  start = Clock::now();
  problem.set_positions(step.x);
  step.energy = problem.local_step();
  step.local_ms += ms_since(start);
}

LineStep armijo_or_plain_step(LocalGlobalProblem& problem, const Eigen::MatrixXd& x, const Eigen::MatrixXd& d,
                              double slope, double energy, ArapReport& report) {
  constexpr double kArmijo = 1e-4; // sufficient-decrease constant c_1 (Nocedal & Wright's usual value)
  constexpr int kTrials = 3;
  LineStep step;
  auto start = Clock::now();
  for (int t = 0; t < kTrials && !step.accepted && slope < 0; ++t) {
    const double alpha = std::ldexp(1.0, -t); // 1, 1/2, 1/4
    step.x = x + alpha * d;
    problem.set_positions(step.x);
    step.energy = problem.local_step();
    step.accepted = step.energy <= energy + kArmijo * alpha * slope; // false for NaN as well
  }
  step.local_ms += ms_since(start);
  if (!step.accepted) {
    ++report.rejected;
    take_plain_step(problem, step);
  }
  return step;
}

// Liu, Bouaziz and Kavan 2017: quasi-Newton on E(x) = min_R energy with H_0 = L_ff^{-1}. The energy is not
// convex, so each step is checked by Armijo backtracking; when that fails, the plain local/global step
// (with no history the L-BFGS step itself) is taken and the history restarts.
void run_lbfgs(LocalGlobalProblem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
               ArapReport& report, Progress& progress) {
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
    LineStep step = armijo_or_plain_step(problem, x, d, slope, energy, report);
    if (!step.accepted) {
      lbfgs.reset();
      quasi_newton = false;
    }
    energy = step.energy;
    start = Clock::now();
    problem.assemble_rhs();
    Eigen::MatrixXd g_next = problem.gradient();
    step.global_ms += ms_since(start);
    start = Clock::now();
    lbfgs.push(step.x, x, g_next, g);
    x.swap(step.x);
    g.swap(g_next);
    report.accelerator_ms += ms_since(start);
    if (progress.record(energy, g.norm(), quasi_newton && step.accepted, step.local_ms, step.global_ms))
      return;
  }
}

// Where the step of length tau along p from d meets the trust region's boundary ||d + tau p||_L = radius:
// the positive root of dLd + 2 tau dLp + tau^2 pLp = radius^2 (dLd <= radius^2, so it exists).
double to_boundary(double dLd, double dLp, double pLp, double radius) {
  const double slack = std::max(0.0, radius * radius - dLd);
  return (std::sqrt(dLp * dLp + pLp * slack) - dLp) / pLp;
}

// Truncated Newton in a trust region (Steihaug-Toint CG, Nocedal & Wright Algorithm 7.2 and Section 4.1) on
// E(x) = min_R energy with the exact Hessian (LocalGlobalProblem::hessian_product). The model
// m(d) = g.d + d.H d / 2 is minimized by conjugate gradients preconditioned by L_ff (the factorization at
// hand) inside ||d||_L <= radius, stopped at ||r|| <= eta ||g|| with eta = min(0.5, sqrt(||g|| / ||g_0||))
// (superlinear convergence near a minimum), after `cg_limit` steps, at the boundary, or at a direction of
// non-positive curvature, which is followed to the boundary. The energy is not convex: on large edits the
// plain step's own direction often has negative curvature, and a line search there either throws away a CG
// iterate blown up by near-zero curvature or creeps with the plain step; the trust region instead starts at
// the plain step's length and doubles while the model predicts the energy well, which walks out of such
// regions at a growing pace. A step that achieves less than kAccept of the predicted decrease is replaced by
// the plain local/global step (never an energy increase), and the radius shrinks.
void run_newton(LocalGlobalProblem& problem, const ArapSolveOptions& options, double energy,
                Eigen::MatrixXd g, ArapReport& report, Progress& progress) {
  constexpr double kAccept = 0.1;                // rho above this: the step is taken
  constexpr double kShrink = 0.25, kGrow = 0.75; // rho below / above: radius shrinks / grows (N&W Alg. 4.1)
  const int cg_limit = options.window;
  const double g0 = g.norm();
  Eigen::MatrixXd x = problem.positions();
  double radius = 0; // in the L_ff norm; set from the first plain step's length
  for (int k = 0; k < options.max_iterations; ++k) {
    auto start = Clock::now();
    problem.prepare_hessian();
    const double g_norm = g.norm();
    const double eta = std::min(0.5, std::sqrt(g_norm / g0));
    Eigen::MatrixXd r = -g;
    Eigen::MatrixXd p = problem.solve(r); // z_0 = L^-1 r_0: the plain step
    double rz = inner(r, p);
    if (radius == 0) radius = std::sqrt(rz); // ||L^-1 g||_L
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(g.rows(), 3);
    // ||d||_L^2, d.L p, p.L p by the preconditioned CG recurrences (no product with L); the model value.
    double dLd = 0, dLp = 0, pLp = rz, model = 0;
    bool boundary = false;
    for (int j = 0; j < cg_limit; ++j) {
      const Eigen::MatrixXd Hp = problem.hessian_product(p);
      const double curvature = inner(p, Hp);
      const double alpha = rz / curvature;
      if (!(curvature > 0) || dLd + 2 * alpha * dLp + alpha * alpha * pLp >= radius * radius) {
        const double tau = to_boundary(dLd, dLp, pLp, radius);
        d += tau * p;
        model += -tau * rz + 0.5 * tau * tau * curvature; // m(d + tau p) - m(d), with r.p = r.z
        dLd = radius * radius;
        boundary = true;
        break;
      }
      d += alpha * p;
      model -= 0.5 * alpha * rz;
      dLd += 2 * alpha * dLp + alpha * alpha * pLp;
      r -= alpha * Hp;
      if (r.norm() <= eta * g_norm || j + 1 == cg_limit) break;
      const Eigen::MatrixXd z = problem.solve(r);
      const double rz_next = inner(r, z);
      const double beta = rz_next / rz;
      dLp = beta * (dLp + alpha * pLp);
      pLp = rz_next + beta * beta * pLp;
      p = z + beta * p;
      rz = rz_next;
    }
    report.accelerator_ms += ms_since(start);
    LineStep step;
    start = Clock::now();
    step.x = x + d;
    problem.set_positions(step.x);
    step.energy = problem.local_step();
    step.local_ms = ms_since(start);
    const double rho = (step.energy - energy) / model; // model < 0; NaN (a non-finite trial) fails below
    step.accepted = model < 0 && rho >= kAccept;
    if (!(rho >= kShrink))
      radius = kShrink * std::sqrt(dLd);
    else if (rho > kGrow && boundary)
      radius *= 2;
    if (!step.accepted) {
      ++report.rejected;
      take_plain_step(problem, step);
    }
    energy = step.energy;
    start = Clock::now();
    problem.assemble_rhs();
    g = problem.gradient();
    step.global_ms += ms_since(start);
    x.swap(step.x);
    if (progress.record(energy, g.norm(), step.accepted, step.local_ms, step.global_ms)) return;
  }
}

} // namespace

ArapReport run_local_global(LocalGlobalProblem& problem, const ArapSolveOptions& options,
                            FactorizationKind factorization, Clock::time_point start) {
  ArapReport report;
  report.accelerator = options.window == 0 ? ArapAccelerator::None : options.accelerator;
  Progress progress(options, report, factorization, start);
  if (report.accelerator == ArapAccelerator::Newton) // it prepares the Hessian after nearly every local step
    problem.keep_covariances();
  auto t = Clock::now();
  const double energy = problem.local_step();
  const double local_ms = ms_since(t);
  t = Clock::now();
  problem.assemble_rhs();
  Eigen::MatrixXd g = problem.gradient();
  if (progress.begin(energy, g.norm(), local_ms, ms_since(t))) return report;
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
  case ArapAccelerator::Newton:
    run_newton(problem, options, energy, std::move(g), report, progress);
    break;
  }
  report.solves = problem.solves();
  return report;
}

} // namespace iarap::detail
