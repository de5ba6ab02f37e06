#include "explain_error.h"

namespace iarap::cli {
namespace {

bool has(const std::string& text, const char* part) {
  return text.find(part) != std::string::npos;
}

} // namespace

std::string name_repair(const std::string& message, const std::string& how) {
  const std::string library = "repair_mesh ", option = " (RepairOptions::";
  const std::size_t at = message.find(library);
  const std::size_t open = at == std::string::npos ? at : message.find(option, at);
  const std::size_t close = open == std::string::npos ? open : message.find(')', open);
  if (close == std::string::npos) return message;
  return message.substr(0, at) + how + " " + message.substr(at + library.size(), open - at - library.size()) +
         message.substr(close + 1);
}

std::vector<std::string> name_repair(const std::vector<std::string>& messages, const std::string& how) {
  std::vector<std::string> named;
  named.reserve(messages.size());
  for (const std::string& message : messages) named.push_back(name_repair(message, how));
  return named;
}

std::string explain_solver_error(const std::string& what, const ErrorContext& context) {
  std::string message = what;
  const std::string info = "`iarap info " + context.mesh + "`";
  const std::string library_option = "enable pin_unconstrained_components";
  if (const auto at = message.find(library_option); at != std::string::npos) {
    message.replace(at, library_option.size(),
                    "pass --pin-unconstrained (pins one vertex of each such part)");
  } else if (has(message, "singular")) {
    message += "\n  cause: the linear system of the free vertices has no unique solution: a part of the mesh "
               "no constraint reaches, or degenerate faces with zero or cancelling weights"
               "\n  fix: see " +
               info +
               "; --repair welds coincident vertices and drops zero-area faces, "
               "--pin-unconstrained holds unconstrained parts, and --method iarap avoids original ARAP's "
               "negative cotangent weights";
  } else if (has(message, "is not finite") && has(message, "entry")) {
    message += "\n  cause: an infinite weight in the system matrix, from a degenerate face (zero area or a "
               "zero-length edge)"
               "\n  fix: --repair drops zero-area faces and welds coincident vertices; " +
               info + " counts them";
  } else if (has(message, "degenerate (zero area)")) {
    message += "\n  fix: --repair drops zero-area faces (" + info + " counts them)";
  } else if (has(message, "tracing intrinsic edge")) {
    message +=
        "\n  cause: an edge of the intrinsic Delaunay triangulation could not be followed across the "
        "input faces, which happens on nearly degenerate faces (slivers, almost coincident vertices)"
        "\n  fix: --repair drops zero-area faces and welds coincident vertices; --method spokes-rims or "
        "--method arap need no tracing";
  }
  if (context.repaired)
    message += "\n  (after --repair: vertex, face and component numbers refer to the repaired mesh, not to " +
               context.mesh + ")";
  return message;
}

} // namespace iarap::cli
