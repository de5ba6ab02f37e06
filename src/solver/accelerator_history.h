// What L-BFGS, Anderson and the hybrid accelerator keep from one arap_solve call to the next
// (ArapSolveOptions::accelerator_history, ArapReport::accelerator_history): L-BFGS's (s, y) pairs, Anderson's
// residual differences, and whether the hybrid's Newton end-game has begun. Its rows are the problem's
// unknowns in the order the problem keeps them (the free vertices in visit order), which is the same from
// one solve on the same data to the next. Internal: callers hold it through the public shared_ptr only.
#pragma once
#include "iarap/solver/arap_types.h"

#include "anderson_acceleration.h"
#include "lbfgs_direction.h"

#include <Eigen/Core>

#include <memory>
#include <optional>

namespace iarap {

struct ArapAcceleratorHistory {
  ArapAccelerator accelerator = ArapAccelerator::None;
  int window = 0;
  Eigen::Index unknowns = 0; // free count x dimension of the problem it was built on
  std::optional<detail::LbfgsDirection> lbfgs;
  std::optional<detail::AndersonAcceleration> anderson;
  bool newton_phase = false; // the hybrid has switched to Newton: the next call goes on with it
};

namespace detail {

// The history a solve continues: options.accelerator_history when it was left by the same accelerator with
// the same window (an empty one of another kind is reset to this kind and starts cold), a new one when
// options gives none. unknowns: the problem's free count x dimension. Throws InputError when the given
// history is of a problem of another size (another data or constrained set: a history holds only for the data
// and targets that built it).
std::shared_ptr<ArapAcceleratorHistory> continued_history(const ArapSolveOptions& options,
                                                          ArapAccelerator accelerator, Eigen::Index unknowns);

} // namespace detail
} // namespace iarap
