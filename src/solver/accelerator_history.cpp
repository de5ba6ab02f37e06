#include "accelerator_history.h"

#include "iarap/core/errors.h"

#include <string>

namespace iarap::detail {

std::shared_ptr<ArapAcceleratorHistory>
continued_history(const ArapSolveOptions& options, ArapAccelerator accelerator, Eigen::Index unknowns) {
  std::shared_ptr<ArapAcceleratorHistory> history = options.accelerator_history;
  if (history && history->unknowns != 0 && history->unknowns != unknowns)
    throw InputError("ARAP: accelerator_history is of a problem with " + std::to_string(history->unknowns) +
                     " unknowns, this one has " + std::to_string(unknowns) +
                     " (a history continues a solve on the same data and constrained set)");
  if (!history) history = std::make_shared<ArapAcceleratorHistory>();
  if (history->accelerator == accelerator && history->window == options.window && history->unknowns != 0)
    return history; // continued
  *history = ArapAcceleratorHistory{};
  history->accelerator = accelerator;
  history->window = options.window;
  history->unknowns = unknowns;
  if (accelerator == ArapAccelerator::Anderson) history->anderson.emplace(options.window, unknowns);
  if (accelerator == ArapAccelerator::Lbfgs || accelerator == ArapAccelerator::Hybrid)
    history->lbfgs.emplace(options.window);
  return history;
}

} // namespace iarap::detail
