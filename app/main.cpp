// Entry point of the iarap tool: builds the subcommands from the registry and maps errors to exit codes.
#include "command_registry.h"
#include "iarap/core/errors.h"
#include "iarap/core/version.h"

#include <algorithm>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"iarap: as-rigid-as-possible surface deformation (original ARAP, spokes-and-rims, iARAP)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "iarap " + iarap::version());
  auto& commands = iarap::cli::command_registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
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
