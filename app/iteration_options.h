// The --iterations and --tolerance options of the subcommands that run a local/global iteration.
#pragma once
#include <CLI/CLI.hpp>

namespace iarap::cli {

// Adds --iterations (0..1000000) and --tolerance (finite, >= 0; the relative energy decrease that stops the
// iteration) to `command`, writing into the two variables and showing their current values as defaults.
void add_iteration_options(CLI::App& command, int& iterations, double& tolerance);

} // namespace iarap::cli
