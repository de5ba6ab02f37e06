// Helpers shared by the tests: where the bundled and the shared meshes are.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <unistd.h>

namespace iarap::test {

// A file under the repository's data/ folder (always present).
inline std::string data_path(const std::string& name) {
  return std::string(IARAP_SOURCE_DIR) + "/data/" + name;
}

// The shared test meshes: $IARAP_SHARED_MESHES, else ../shared/meshes beside the repository.
// Returns an empty string when the folder or file is absent; callers GTEST_SKIP() with a message (or use
// shared_mesh_or_skip / shared_mesh_in_loop below, which honour IARAP_REQUIRE_SHARED_MESHES).
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

// True when IARAP_REQUIRE_SHARED_MESHES=1 (CI sets it): a missing shared mesh then fails the test instead of
// skipping it, so that CI with an incomplete ../shared cannot stay green.
inline bool shared_meshes_required() {
  const char* env = std::getenv("IARAP_REQUIRE_SHARED_MESHES");
  return env != nullptr && std::string(env) == "1";
}

// For a loop over shared meshes: the path, or "" after recording a failure (required) or printing a note
// (not required) for a missing one; the caller skips that mesh.
inline std::string shared_mesh_in_loop(const std::string& name) {
  const std::string path = shared_mesh_path(name);
  if (path.empty()) {
    if (shared_meshes_required())
      ADD_FAILURE() << "shared mesh " << name << " is missing and IARAP_REQUIRE_SHARED_MESHES=1";
    else
      std::cout << "note: shared mesh " << name << " not found; left out of this test\n";
  }
  return path;
}

// A fresh temporary directory for one test's outputs.
inline std::filesystem::path temp_dir(const std::string& tag) {
  auto dir =
      std::filesystem::temp_directory_path() / ("iarap_test_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

} // namespace iarap::test

// Declares `const std::string var` = the path of shared mesh `name`; skips the test when it is absent, or
// fails it when IARAP_REQUIRE_SHARED_MESHES=1.
#define IARAP_SHARED_MESH_OR_SKIP(var, name)                                                                 \
  const std::string var = ::iarap::test::shared_mesh_path(name);                                             \
  if (var.empty()) {                                                                                         \
    if (::iarap::test::shared_meshes_required())                                                             \
      FAIL() << "shared mesh " << (name) << " is missing and IARAP_REQUIRE_SHARED_MESHES=1";                 \
    GTEST_SKIP() << "shared mesh " << (name) << " not found (../shared/meshes or $IARAP_SHARED_MESHES)";     \
  }
