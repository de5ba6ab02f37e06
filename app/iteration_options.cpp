#include "iteration_options.h"

#include "number_validators.h"

namespace iarap::cli {

void add_iteration_options(CLI::App& command, int& iterations, double& tolerance) {
  command.add_option("--iterations", iterations, "Maximum number of local/global iterations (>= 0)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command
      .add_option("--tolerance", tolerance,
                  "Stop when the energy decreases by at most this fraction of itself in one iteration (>= 0)")
      ->check(finite_non_negative)
      ->capture_default_str();
}

} // namespace iarap::cli
