// The hybrid accelerator (ArapAccelerator::Hybrid): L-BFGS while it makes progress, then Newton's trust
// region for the end-game. On bend60 (`iarap bench --converge 1e-6`, beetle, docs/accelerators.md#hybrid)
// L-BFGS's steps, one solve each, reach a 1e-2 gap in 26 (iARAP) / 19 (spokes-rims) iterations where
// Newton's first iterations run all their CG steps at a short trust radius (12 / 13 iterations, 8 solves
// each); L-BFGS's tail is linear (225 / 146 iterations to 1e-6 against Newton's 46 / 40). Internal to the
// solver (run_local_global picks it).
#pragma once
#include "iarap/solver/arap_types.h"

#include "accelerator_history.h"
#include "problem.h"
#include "stopping.h"

#include <Eigen/Core>

namespace iarap::detail {

// When the early phase has stalled: the energy's mean relative decrease over the last kSpan iterations has
// fallen to kStall (scale-free: energies of any unit, meshes of any size; the mean, because L-BFGS's
// decreases alternate by up to 2x from one iteration to the next). kStall = 3e-4 from bend60 on the beetle
// (docs/accelerators.md#hybrid): with 3e-3 and 1e-3 the switch came before the 1e-2 gap on iARAP, so that
// Newton's costly first iterations came back; 1e-4 ran L-BFGS's linear middle longer (91 iterations to
// 1e-6 against 77) without fewer solves.
class StallRule {
public:
  static constexpr int kSpan = 3;
  static constexpr double kStall = 3e-4;
  // Takes the energy after each iteration; true once the rule holds.
  bool stalled(double energy);

private:
  double recent_[kSpan + 1] = {};
  int seen_ = 0;
};

// Iterations from the problem's current point (energy `energy`, gradient g) until report.iterations reaches
// options.max_iterations or a stopping rule holds: L-BFGS on history.lbfgs until StallRule says it stalls,
// then Newton (history.newton_phase: a continued solve goes on with Newton at once). Newton's reference
// gradient is options.newton_reference_gradient, or ||g|| where this solve began.
void run_hybrid(Problem& problem, const ArapSolveOptions& options, double energy, Eigen::MatrixXd g,
                ArapAcceleratorHistory& history, ArapReport& report, Progress& progress);

} // namespace iarap::detail
