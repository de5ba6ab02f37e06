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

// The web app folder `iarap serve` uses without --app-dir: the first of these that holds an index.html,
// else "" (serve then asks for --app-dir):
//  1. <folder of the running executable>/from_executable, so that an installed tool finds
//     <prefix>/share/iarap/web at any prefix, also after the prefix was moved;
//  2. build_tree_web_dir, the source checkout's web/ the build was configured from.
std::filesystem::path default_web_root(const std::filesystem::path& from_executable,
                                       const std::filesystem::path& build_tree_web_dir);

} // namespace iarap::serve
