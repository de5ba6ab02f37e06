// When arap_solve stops: records each accepted iterate in the report and applies the stopping rules of
// ArapSolveOptions (relative energy decrease, gradient norm, the callback). Internal to the solver.
#pragma once
#include "iarap/core/stopwatch.h"
#include "iarap/solver/arap_types.h"

#include "problem.h"

namespace iarap::detail {

class Progress {
public:
  // start: when arap_solve began (report.elapsed_ms counts from it).
  Progress(const ArapSolveOptions& options, ArapReport& report, FactorizationKind factorization,
           Clock::time_point start)
      : options_(options), report_(report), factorization_(factorization), start_(start) {}

  // The initial guess. Returns true when the gradient rule already holds (a zero gradient). Throws
  // SolverError when its energy is not finite.
  bool begin(double energy, double gradient_norm, double local_ms, double global_ms);

  // Iterate k + 1. Returns true when the solve is to stop. Throws SolverError naming the iteration and the
  // factorization when the energy is not finite.
  bool record(double energy, double gradient_norm, bool accelerated, double local_ms, double global_ms);

private:
  const ArapSolveOptions& options_;
  ArapReport& report_;
  FactorizationKind factorization_;
  Clock::time_point start_;
  double previous_ = 0;
};

// The global step's tail shared by all loops: the right-hand side at the new iterate and the norm of the
// gradient there (Problem::assemble_rhs).
inline double rhs_and_gradient_norm(Problem& problem) {
  return problem.assemble_rhs_gradient_norm();
}

} // namespace iarap::detail
