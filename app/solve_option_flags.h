// The solve options' command-line flags (`iarap deform`, `iarap simulate`), made from the schema of
// iarap/solver/solve_option_fields.h: one flag per field, with its doc, range and unit as --help text.
#pragma once
#include "iarap/solver/arap_types.h"

#include <CLI/CLI.hpp>

namespace iarap::cli {

// Adds the flag of every solve option to `command`. A given flag sets its member of `options` (which must
// outlive the parse); --help shows the value `options` holds now as the default. A bad value is a usage
// error (exit 2) whose message is the library's (solve_option_error): "--tolerance: tolerance must be a
// finite number; got nan".
void add_solve_option_flags(CLI::App& command, ArapSolveOptions& options);

} // namespace iarap::cli
