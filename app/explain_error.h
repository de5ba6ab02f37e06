// Turns the library's errors into messages for a user of the tool: what is wrong, where, and which flag
// of `iarap deform` fixes it (the library names its own options, the tool its flags).
#pragma once
#include <string>

namespace iarap::cli {

struct ErrorContext {
  std::string mesh;      // the input mesh path, for `iarap info MESH`
  bool repaired = false; // --repair ran: numbers in the message refer to the repaired mesh
};

// The message of an error from arap_precompute / arap_solve, with its cause and fix added where known.
std::string explain_solver_error(const std::string& what, const ErrorContext& context);

} // namespace iarap::cli
