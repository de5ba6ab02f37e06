// The constraints the solver sees for one solve request: the constrained vertices (fixed ++ handle) are
// hard, unless the request gives the handle weights (a soft handle, dragged with a pull of weight w per
// vertex, penalty w |u_i - t_i|^2): then only the fixed vertices are hard and the handle vertices join the
// loaded file's soft vertices, after them, with their targets. The shape then lags behind a soft handle's
// targets by an amount that shrinks as the weight grows, and tends to the hard solution as w -> inf.
#pragma once
#include "iarap/scene/constraint_set.h"

#include <Eigen/Core>
#include <optional>

namespace iarap::serve {

struct SolverConstraints {
  Eigen::VectorXi hard;         // the fixed set of arap_precompute / arap_solve
  Eigen::MatrixXd hard_targets; // #hard x 3
  SoftConstraintSet soft;       // with targets; soft_targets_of(soft) gives arap_solve's soft targets
  bool soft_handle = false;
};

// fixed, handle: the session's sets; targets: #fixed + #handle x 3 (fixed rows first); file_soft: the loaded
// file's soft constraints with their targets for the request; handle_weights: #handle weights, or none for a
// hard handle. Throws InputError for weights given without a handle vertex, of the wrong count, or not
// finite and > 0 (naming the position).
SolverConstraints solver_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                                     const Eigen::MatrixXd& targets, const SoftConstraintSet& file_soft,
                                     const std::optional<Eigen::VectorXd>& handle_weights);

// Sets set's vertex, face and hard targets from T, #points x 3 in the solver's order (soft_targets_of's).
void set_soft_targets(SoftConstraintSet& set, const Eigen::MatrixXd& T);

// a == b as index lists (sizes first, so that lists of different lengths compare unequal).
bool same_indices(const Eigen::VectorXi& a, const Eigen::VectorXi& b);

} // namespace iarap::serve
