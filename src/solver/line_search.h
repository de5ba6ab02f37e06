// Steps along a descent direction for the accelerated loops (L-BFGS, Newton): Armijo backtracking, and the
// plain local/global step that replaces a rejected trial (it never increases the energy while L_ff is
// positive definite). Internal to the solver.
#pragma once
#include "iarap/solver/arap_types.h"

#include "problem.h"

#include <Eigen/Core>

namespace iarap::detail {

// Where a step ended; the local step at x is done (problem holds x and its rotations).
struct LineStep {
  Eigen::MatrixXd x;
  double energy = 0;
  bool accepted = false; // false: the plain step
  double local_ms = 0, global_ms = 0;
};

// Replaces a rejected trial by the plain local/global step from the point whose right-hand side the problem
// last assembled; the trial's time stays in the step's.
void take_plain_step(Problem& problem, LineStep& step);

// For an accelerated step that the feasible set shortened (Problem::step_limit < 1): the plain step too, and
// whichever of the two has the lower energy. The models of L-BFGS and Newton do not see the bound, and the
// step cut at it can be far shorter than the plain step, whose preconditioned direction the problem's
// barrier bends away from it (measured on camelhead's flip-free map: Newton alone stalled at E 1.90 where
// the plain iteration reaches 0.80). Leaves the problem at the chosen point; step.accepted is false when
// the plain step won.
void lower_of_step_and_plain(Problem& problem, LineStep& step);

// Armijo backtracking from x along d (slope = g . d) with lengths 1, 1/2, 1/4 (a quasi-Newton or Newton step
// that needs more halving has a poor curvature model, and the plain step costs no more than one more
// trial), each times min(1, problem.step_limit(x, d)) so that no trial leaves the feasible set; when none
// passes, or d is not a descent direction (slope >= 0), the plain step (the right-hand side still belongs to
// x) and report.rejected + 1.
LineStep armijo_or_plain_step(Problem& problem, const Eigen::MatrixXd& x, const Eigen::MatrixXd& d,
                              double slope, double energy, ArapReport& report);

} // namespace iarap::detail
