// Internal: the lower-case extension of a path ("mesh.OBJ" -> ".obj"), for the read_mesh/write_mesh dispatch.
#pragma once
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace iarap::io_detail {

inline std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

} // namespace iarap::io_detail
