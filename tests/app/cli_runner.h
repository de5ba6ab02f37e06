// Runs the built iarap tool (IARAP_CLI_PATH) through the shell for the end-to-end tests.
#pragma once
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace iarap::test::cli {

struct CliRun {
  int code = -1;
  std::string out; // stdout (stderr too when asked)
};

// Runs a shell command line; stderr goes to the test log unless merge_stderr.
inline CliRun run_command(const std::string& line, bool merge_stderr = false) {
  const std::string command = line + (merge_stderr ? " 2>&1" : "");
  CliRun run;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) run.out.append(buffer, n);
  const int status = ::pclose(pipe);
  run.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

// Runs `iarap ARGS`; stderr goes to the test log unless merge_stderr.
inline CliRun iarap_cli(const std::string& args, bool merge_stderr = false) {
  return run_command(std::string("'") + IARAP_CLI_PATH + "' " + args, merge_stderr);
}

// Runs `iarap ARGS` under `env ENV` (e.g. "-u NAME" or "NAME=value").
inline CliRun iarap_cli_env(const std::string& env, const std::string& args) {
  return run_command("env " + env + " '" + std::string(IARAP_CLI_PATH) + "' " + args);
}

inline nlohmann::json parse_json(const CliRun& run) {
  try {
    return nlohmann::json::parse(run.out);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "):\n" << run.out;
    return nlohmann::json::object();
  }
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

} // namespace iarap::test::cli
