// Entry point of the iarap tool: builds the subcommands from the registry and maps errors to exit codes.
#include "command_registry.h"
#include "iarap/core/errors.h"
#include "iarap/core/version.h"

#include <algorithm>
#include <iostream>
#include <string>

namespace {

// The subcommand a command line names: its first word that is not an option (the tool itself takes only
// --help and --version, which take no value). Empty when there is none.
std::string first_word(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') return argv[i];
  return {};
}

// CLI11 takes an unknown first word for an extra positional and answers "A subcommand is required"; the
// user is told the word and the commands instead.
bool is_unknown_command(const std::string& word, const std::vector<iarap::cli::Command>& commands) {
  return !word.empty() && std::none_of(commands.begin(), commands.end(),
                                       [&](const iarap::cli::Command& c) { return c.name == word; });
}

std::string command_names(const std::vector<iarap::cli::Command>& commands) {
  std::string names;
  for (const auto& command : commands) names += (names.empty() ? "" : ", ") + command.name;
  return names;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"iarap: as-rigid-as-possible surface deformation (original ARAP, spokes-and-rims, iARAP)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "iarap " + iarap::version());
  auto& commands = iarap::cli::command_registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  const std::string word = first_word(argc, argv);
  if (is_unknown_command(word, commands)) {
    std::cerr << "iarap: error: unknown subcommand '" << word
              << "'; expected one of: " << command_names(commands) << " (iarap --help lists them)\n";
    return 2;
  }
  for (const auto& command : commands) command.setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e); // prints help or the usage error
    return code == 0 ? 0 : 2;
  } catch (const iarap::Error& e) {
    std::cerr << "iarap: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "iarap: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
