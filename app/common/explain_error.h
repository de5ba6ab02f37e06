// Turns the library's errors into messages for a user of the tool: what is wrong, where, and which flag
// of `iarap deform` fixes it (the library names its own options, the tool its flags).
#pragma once
#include <string>
#include <vector>

namespace iarap::cli {

struct ErrorContext {
  std::string mesh;      // the input mesh path, for `iarap info MESH`
  bool repaired = false; // --repair ran: numbers in the message refer to the repaired mesh
};

// The message of an error from arap_precompute / arap_solve, with its cause and fix added where known.
std::string explain_solver_error(const std::string& what, const ErrorContext& context);

// The flag of `iarap deform` that runs repair_mesh, for the tool's messages.
inline constexpr const char* deform_repair_flag = "`iarap deform --repair`";

// A check_mesh message with the library's repair ("; repair_mesh welds them (RepairOptions::weld)") named
// the way this front-end does it (`how`: "; `iarap deform --repair` welds them"); other messages as they
// are.
std::string name_repair(const std::string& message, const std::string& how);
std::vector<std::string> name_repair(const std::vector<std::string>& messages, const std::string& how);

} // namespace iarap::cli
