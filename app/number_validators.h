// Validators of numeric options shared by the subcommands.
#pragma once
#include <CLI/CLI.hpp>

namespace iarap::cli {

// CLI::NonNegativeNumber lets nan through (then a runtime error, exit 1) and words its range with the
// 309 digits of DBL_MAX; this one is a usage error (exit 2) in plain words.
extern const CLI::Validator finite_non_negative;
// A finite number > 0 (the time step), and any finite number (gravity's components), as usage errors.
extern const CLI::Validator finite_positive;
extern const CLI::Validator finite_number;

} // namespace iarap::cli
