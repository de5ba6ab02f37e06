// Subcommands of the iarap tool register themselves here, one file per subcommand, so that adding a
// command touches no other file. Exit codes: 0 ok, 1 runtime error, 2 usage error.
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace iarap::cli {

struct Command {
  std::string name;
  // Adds the subcommand (options and callback) to the app. The callback throws iarap::Error on a
  // runtime failure and CLI::Error on a usage error; main() maps them to exit codes 1 and 2.
  std::function<void(CLI::App&)> setup;
};

inline std::vector<Command>& command_registry() {
  static std::vector<Command> commands;
  return commands;
}

// Use at namespace scope in a command's .cpp: static const bool registered = register_command({...});
inline bool register_command(Command command) {
  command_registry().push_back(std::move(command));
  return true;
}

} // namespace iarap::cli
