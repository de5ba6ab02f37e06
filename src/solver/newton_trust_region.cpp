#include "newton_trust_region.h"

#include "iarap/core/stopwatch.h"

#include "inner.h"
#include "line_search.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace iarap::detail {
namespace {

// Where the step of length tau along p from d meets the trust region's boundary ||d + tau p||_L = radius:
// the positive root of dLd + 2 tau dLp + tau^2 pLp = radius^2 (dLd <= radius^2, so it exists).
double to_boundary(double dLd, double dLp, double pLp, double radius) {
  const double slack = std::max(0.0, radius * radius - dLd);
  return (std::sqrt(dLp * dLp + pLp * slack) - dLp) / pLp;
}

// The Steihaug-Toint step: d minimizing the model m(d) = g.d + d.H d / 2 (model = m(d) < 0 unless g = 0),
// ||d||_L^2 = dLd, and whether it stopped at the trust region's boundary. radius (in the L_ff norm) is set
// from the plain step's length when it is 0. Needs problem.prepare_hessian() at the current point.
struct SteihaugStep {
  Eigen::MatrixXd d;
  double model = 0, dLd = 0;
  bool boundary = false;
};

// should_yield (ArapSolveOptions::should_yield): checked after each CG step that did not stop; true stops.
SteihaugStep steihaug_cg(Problem& problem, const Eigen::MatrixXd& g, double g0, double& radius, int cg_limit,
                         const std::function<bool()>& should_yield) {
  const double g_norm = g.norm();
  const double eta = std::min(0.5, std::sqrt(g_norm / g0));
  Eigen::MatrixXd r = -g;
  Eigen::MatrixXd p = problem.solve(r); // z_0 = L^-1 r_0: the plain step
  double rz = inner(r, p);
  if (radius == 0) radius = std::sqrt(rz); // ||L^-1 g||_L
  SteihaugStep step;
  step.d = Eigen::MatrixXd::Zero(g.rows(), g.cols());
  Eigen::MatrixXd& d = step.d;
  // ||d||_L^2, d.L p, p.L p by the preconditioned CG recurrences (no product with L); the model value.
  double dLd = 0, dLp = 0, pLp = rz, model = 0;
  for (int j = 0; j < cg_limit; ++j) {
    const Eigen::MatrixXd Hp = problem.hessian_product(p);
    const double curvature = inner(p, Hp);
    const double alpha = rz / curvature;
    if (!(curvature > 0) || dLd + 2 * alpha * dLp + alpha * alpha * pLp >= radius * radius) {
      const double tau = to_boundary(dLd, dLp, pLp, radius);
      d += tau * p;
      model += -tau * rz + 0.5 * tau * tau * curvature; // m(d + tau p) - m(d), with r.p = r.z
      dLd = radius * radius;
      step.boundary = true;
      break;
    }
    d += alpha * p;
    model -= 0.5 * alpha * rz;
    dLd += 2 * alpha * dLp + alpha * alpha * pLp;
    r -= alpha * Hp;
    if (r.norm() <= eta * g_norm || j + 1 == cg_limit || (should_yield && should_yield())) break;
    const Eigen::MatrixXd z = problem.solve(r);
    const double rz_next = inner(r, z);
    const double beta = rz_next / rz;
    dLp = beta * (dLp + alpha * pLp);
    pLp = rz_next + beta * beta * pLp;
    p = z + beta * p;
    rz = rz_next;
  }
  step.model = model;
  step.dLd = dLd;
  return step;
}

// The step shortened to t = problem.step_limit(x, d) when that is below 1 (injective UV maps), with its
// model m(t d) = t g.d + t^2 (m(d) - g.d) (the quadratic part of m(d) is m(d) - g.d) and the L norm scaled;
// it no longer ends on the trust region's boundary. Unchanged without a bound. Returns whether it shortened.
bool shorten_to_feasible(const Problem& problem, const Eigen::MatrixXd& x, const Eigen::MatrixXd& g,
                         SteihaugStep& step) {
  const double t = problem.step_limit(x, step.d);
  if (!(t < 1)) return false;
  const double slope = inner(g, step.d);
  step.d *= t;
  step.model = t * slope + t * t * (step.model - slope);
  step.dLd *= t * t;
  step.boundary = false;
  return true;
}

} // namespace

// Truncated Newton in a trust region (Steihaug-Toint CG, Nocedal & Wright Algorithm 7.2 and Section 4.1) on
// E(x) = min_R energy with the exact Hessian (Problem::hessian_product). The model
// m(d) = g.d + d.H d / 2 is minimized by conjugate gradients preconditioned by L_ff (the factorization at
// hand) inside ||d||_L <= radius, stopped at ||r|| <= eta ||g|| with eta = min(0.5, sqrt(||g|| / ||g_0||))
// (superlinear convergence near a minimum), after `cg_limit` steps, at the boundary, or at a direction of
// non-positive curvature, which is followed to the boundary. The energy is not convex: on large edits the
// plain step's own direction often has negative curvature, and a line search there either throws away a CG
// iterate blown up by near-zero curvature or creeps with the plain step; the trust region instead starts at
// the plain step's length and doubles while the model predicts the energy well, which walks out of such
// regions at a growing pace. A step that achieves less than kAccept of the predicted decrease is replaced by
// the plain local/global step (never an energy increase), and the radius shrinks.
void run_newton(Problem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
                ArapReport& report, Progress& progress) {
  constexpr double kAccept = 0.1;                // rho above this: the step is taken
  constexpr double kShrink = 0.25, kGrow = 0.75; // rho below / above: radius shrinks / grows (N&W Alg. 4.1)
  // The energy's rounding level in units of eps |E|: a sum over the cells; on the 43K drag start the ratio
  // turned to noise at a predicted decrease of 4e-15 |E| (about 20 eps |E|).
  constexpr double kRoundingLevel = 100;
  const double g0 = options.newton_reference_gradient > 0 ? options.newton_reference_gradient
                                                          : report.initial_gradient_norm;
  Eigen::MatrixXd x = problem.positions();
  // In the L_ff norm; 0: set from the first plain step's length.
  double radius = options.newton_trust_radius > 0 ? options.newton_trust_radius : 0;
  while (report.iterations < options.max_iterations) {
    bool shortened = false;
    SteihaugStep cg = timed(report.accelerator_ms, [&] {
      problem.prepare_hessian();
      SteihaugStep d = steihaug_cg(problem, g, g0, radius, options.window, options.should_yield);
      shortened = shorten_to_feasible(problem, x, g, d);
      return d;
    });
    LineStep step;
    {
      const ScopedTimer timer(step.local_ms);
      step.x = x + cg.d;
      problem.set_positions(step.x);
      step.energy = problem.local_step();
    }
    // rho = achieved / predicted decrease, both raised by the energy's rounding level (Conn, Gould & Toint,
    // Trust-Region Methods, 17.4.2): once the predicted decrease falls to that level, the two energies
    // differ by rounding alone and their raw ratio is noise that collapses the radius (a 43K drag start:
    // from 2e-2 to 3e-8 in one step, then to 1e-150, and 2000 iterations, 1682 of them rejected, at a
    // stationary point whose gradient rule had not yet held); with the shift such a step counts as modelled
    // (rho near 1), and the energy it may add is below that level. Far above it the ratio is the plain one.
    // model < 0; NaN (a non-finite trial) fails below.
    const double rounding = kRoundingLevel * std::numeric_limits<double>::epsilon() * std::abs(energy);
    const double rho = (energy - step.energy + rounding) / (rounding - cg.model);
    step.accepted = cg.model < 0 && rho >= kAccept;
    if (!(rho >= kShrink))
      radius = kShrink * std::sqrt(cg.dLd);
    else if (rho > kGrow && cg.boundary)
      radius *= 2;
    if (!step.accepted) {
      ++report.rejected;
      take_plain_step(problem, step);
    } else if (shortened) {
      lower_of_step_and_plain(problem, step);
    }
    energy = step.energy;
    timed(step.global_ms, [&] {
      problem.assemble_rhs();
      g = problem.gradient();
    });
    x.swap(step.x);
    report.newton_trust_radius = radius;
    report.newton_reference_gradient = g0;
    if (progress.record(energy, g.norm(), step.accepted, step.local_ms, step.global_ms)) return;
  }
}

} // namespace iarap::detail
