// Helpers shared by the tests: where the bundled and the shared meshes are.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace iarap::test {

// A file under the repository's data/ folder (always present).
inline std::string data_path(const std::string& name) {
  return std::string(IARAP_SOURCE_DIR) + "/data/" + name;
}

// The shared test meshes: $IARAP_SHARED_MESHES, else ../shared/meshes beside the repository.
// Returns an empty string when the folder or file is absent; callers GTEST_SKIP() with a message.
inline std::string shared_mesh_path(const std::string& name) {
  std::filesystem::path dir;
  if (const char* env = std::getenv("IARAP_SHARED_MESHES")) {
    dir = env;
  } else {
    dir = std::filesystem::path(IARAP_SOURCE_DIR).parent_path() / "shared" / "meshes";
  }
  std::filesystem::path p = dir / name;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

// A fresh temporary directory for one test's outputs.
inline std::filesystem::path temp_dir(const std::string& tag) {
  auto dir = std::filesystem::temp_directory_path() / ("iarap_test_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

} // namespace iarap::test
