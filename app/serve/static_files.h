// Which file under the web app folder a GET path names, if any: the only files the server ever reads on a
// client's behalf. Allowed: the app's own files (index.html, *.css, src/*.js) and three.js's ES modules
// (node_modules/three/build/, node_modules/three/examples/jsm/). Every path component must be a plain
// name ([A-Za-z0-9_.-], not starting with '.'), so "..", hidden files and encoded separators never
// match, and the resolved file (symlinks followed) must still lie inside the app folder.
#pragma once
#include <filesystem>
#include <optional>
#include <string>

namespace iarap::serve {

struct StaticFile {
  std::filesystem::path path;
  std::string content_type;
};

// request_path: the decoded URL path ("/" means index.html). nullopt: not an allowed, existing file.
std::optional<StaticFile> resolve_static_file(const std::filesystem::path& app_dir,
                                              const std::string& request_path);

} // namespace iarap::serve
