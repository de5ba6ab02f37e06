// What `iarap serve` was started with (serve_command.cpp): the web app folder, the server's meshes and the
// limits every route applies.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace iarap::serve {

struct ServerMesh {
  std::string name; // what clients see and ask for
  std::string path; // known to the server only
};

struct ServeConfig {
  std::filesystem::path app_dir;
  std::vector<ServerMesh> meshes;
  std::size_t max_json_bytes = std::size_t{16} << 20;
  std::size_t max_upload_bytes = std::size_t{64} << 20;
  int max_iterations = 1000;
  // Host header values accepted ("127.0.0.1:8080"...), against DNS rebinding; empty: any.
  std::vector<std::string> allowed_hosts;
  bool verbose = false;
};

} // namespace iarap::serve
