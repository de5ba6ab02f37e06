#include "static_files.h"

#include <array>
#include <utility>
#include <vector>

namespace iarap::serve {
namespace {

bool plain_name(const std::string& name) {
  if (name.empty() || name.size() > 128 || name[0] == '.') return false;
  for (const char ch : name) {
    const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
                    ch == '_' || ch == '-' || ch == '.';
    if (!ok) return false;
  }
  return true;
}

std::optional<std::string> content_type_of(const std::string& name) {
  static const std::array<std::pair<const char*, const char*>, 6> types = {{
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".png", "image/png"},
      {".svg", "image/svg+xml"},
      {".ico", "image/x-icon"},
  }};
  for (const auto& [extension, type] : types) {
    const std::string ext = extension;
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0)
      return std::string(type);
  }
  return std::nullopt;
}

// Folders (as component lists) whose files, at any depth, may be served; {} is the top level only.
bool allowed_location(const std::vector<std::string>& parts) {
  const std::size_t depth = parts.size() - 1; // folders above the file
  if (depth == 0) return true;
  if (parts[0] == "src") return true;
  if (parts[0] == "node_modules" && depth >= 3 && parts[1] == "three")
    return parts[2] == "build" || (depth >= 4 && parts[2] == "examples" && parts[3] == "jsm");
  return false;
}

bool inside(const std::filesystem::path& root, const std::filesystem::path& file) {
  auto r = root.begin();
  auto f = file.begin();
  for (; r != root.end(); ++r, ++f) {
    if (f == file.end() || *r != *f) return false;
  }
  return true;
}

} // namespace

std::optional<StaticFile> resolve_static_file(const std::filesystem::path& app_dir,
                                              const std::string& request_path) {
  if (request_path.empty() || request_path[0] != '/' || request_path.size() > 512) return std::nullopt;
  const std::string relative = request_path == "/" ? "index.html" : request_path.substr(1);
  std::vector<std::string> parts;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = relative.find('/', begin);
    parts.push_back(relative.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (!plain_name(parts.back()) || parts.size() > 12) return std::nullopt;
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  const std::optional<std::string> type = content_type_of(parts.back());
  if (!type || !allowed_location(parts)) return std::nullopt;

  std::error_code error;
  const std::filesystem::path root = std::filesystem::canonical(app_dir, error);
  if (error) return std::nullopt;
  std::filesystem::path candidate = root;
  for (const auto& part : parts) candidate /= part;
  const std::filesystem::path file = std::filesystem::canonical(candidate, error);
  if (error || !inside(root, file) || !std::filesystem::is_regular_file(file, error)) return std::nullopt;
  return StaticFile{file, *type};
}

std::filesystem::path default_web_root(const std::filesystem::path& from_executable,
                                       const std::filesystem::path& build_tree_web_dir) {
  std::error_code error;
  std::vector<std::filesystem::path> candidates;
  // Linux names the running executable here, whatever argv[0] or PATH said; symlinks are resolved.
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error && !from_executable.empty()) candidates.push_back(executable.parent_path() / from_executable);
  if (!build_tree_web_dir.empty()) candidates.push_back(build_tree_web_dir);
  for (const auto& folder : candidates) {
    if (std::filesystem::is_regular_file(folder / "index.html", error)) return folder.lexically_normal();
  }
  return {};
}

} // namespace iarap::serve
