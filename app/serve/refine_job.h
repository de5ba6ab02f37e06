// The background refinement's work: after a drag's answer, keep solving toward the same targets in chunks
// of a time budget, each ending in a frame (FrameBoard). The thread that runs the chunks and yields to
// requests is SharedSession's (shared_session.h); this file holds what a chunk computes.
//
// Its stopping rule is the request's tolerance read as a gap to the minimum, made independent of where the
// chunks begin: the energy rule counts only accelerated iterates (a fallback plain step of Newton, L-BFGS or
// Anderson decreases the energy little far from the minimum: 5e-7 of it at a 5e-4 gap on the beetle, which
// stopped the refinement there), and one decrease below the tolerance is not enough (a step the trust
// region cut short stopped the beetle's refinement at a gap of 1.1e-6 to 2.2e-6 with a tolerance of 1e-6):
// the gap left is estimated from the last two decreases (refinement_converged) and held to a quarter of the
// tolerance (refine_job.cpp: the estimate ran short by up to 2.3 times). The gradient rule compares
// with the gradient at the solve's initial guess.
#pragma once
#include "frame_board.h"
#include "solve_request.h"

#include "iarap/solver/arap.h"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>

namespace iarap::serve {

struct RefineJob {
  ArapMethod method = ArapMethod::Iarap;
  Eigen::MatrixXd targets, soft_targets; // options.forces: the solve's
  ArapSolveOptions options;              // max_iterations: the iterations left
  double tolerance = 0;                  // the energy rule (refinement_converged)
  double gradient_target = 0;            // stop once ||g|| <= this (0: no gradient rule)
  double gradient_now = 0;               // ||g|| at the method's U
  // Newton's trust radius and reference gradient, carried from the answer to the first chunk and from
  // chunk to chunk (same targets). Not from one answer to the next: carried over moved targets, the
  // radius of the previous step let the first steps of the beetle's drag run far (its last answer's
  // energy was 400 times the minimum's instead of 1.2 times).
  double trust_radius = 0, reference_gradient = 0;
  // L-BFGS's pairs, Anderson's differences, the hybrid's phase (ArapSolveOptions::accelerator_history):
  // carried the same way, from the answer and from chunk to chunk, never over moved targets.
  std::shared_ptr<ArapAcceleratorHistory> history;
  int iterations_done = 0;
  // The relative decreases of the two counted iterates before (0: none yet), the later one second.
  std::array<double, 2> earlier_decreases{0, 0};
};

// The energy rule of the refinement: with d the relative decrease of the last counted iterate and
// earlier = {d_2, d_1} those of the two before, the decreases shrink at the rate r = max(d / d_1, d_1 / d_2)
// (the slower of the last two: Newton's steps cut short by the trust region shrink unevenly), and if they
// go on shrinking so the gap left after the last is d r / (1 - r) (a geometric series). True when
// d <= tolerance and that estimate is too, or when d <= 100 eps (no iterate gains more than the rounding
// of the energy's sum: the minimum to rounding). False without a previous decrease (d_1 <= 0; without d_2 the
// one rate d / d_1 counts) and when the decreases do not shrink.
bool refinement_converged(const std::array<double, 2>& earlier, double decrease, double tolerance);

// (E_prev - E) / |E_prev| of the report's last iteration: what the energy tolerance compares.
double last_relative_decrease(const ArapReport& report);
// The energy after the report's last iteration (the initial one without iterations).
double last_energy(const ArapReport& report);

// The job that goes on from a solve's answer (report) toward its targets; forces: the solve's (0 x 0: none).
RefineJob refine_job_after(const SolveRequest& request, const ArapReport& report, Eigen::MatrixXd targets,
                           Eigen::MatrixXd soft_targets, Eigen::MatrixXd forces);

// One chunk of job from U: solves for about budget_ms (the last iteration may run over), stopping early at
// the job's rules or at an iteration boundary where keep_going() is false (a request waits for the
// session). U becomes the last finished iterate; the job counts the iterations and carries Newton's
// state. iteration_done, when given, is called at each iteration's end before keep_going (SharedSession
// counts what a waiting request cost). The frame (positions, energy, refining: more chunks are due) is
// not numbered yet; a solver error ends the job with frame.error and U unchanged.
SessionFrame refine_chunk(RefineJob& job, ArapData& data, Eigen::MatrixXd& U, double budget_ms,
                          const std::function<bool()>& keep_going,
                          const std::function<void()>& iteration_done = {});

// The frame that says the refinement was stopped at U: the energy the solves report, E_ARAP + P - f . (U -
// V).
SessionFrame stopped_refinement_frame(const RefineJob& job, const ArapData& data, const Eigen::MatrixXd& U,
                                      const Eigen::MatrixXd& V);

// #X.rows() * #X.cols() floats, row-major: the positions of a frame.
std::vector<float> to_float_rows(const Eigen::MatrixXd& X);

} // namespace iarap::serve
