// Where the benchmarks find the shared test meshes: $IARAP_SHARED_MESHES, else ../shared/meshes beside the
// repository.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <string>

namespace iarap::bench {

// The path of shared mesh `name`, or "" when it is absent (the benchmark then leaves it out).
inline std::string shared_mesh(const std::string& name) {
  const char* env = std::getenv("IARAP_SHARED_MESHES");
  const std::filesystem::path dir =
      env ? std::filesystem::path(env)
          : std::filesystem::path(IARAP_SOURCE_DIR).parent_path() / "shared" / "meshes";
  const std::filesystem::path p = dir / name;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

} // namespace iarap::bench
