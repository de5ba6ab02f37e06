#include "client_names.h"

#include <algorithm>
#include <cctype>

namespace iarap::serve {

std::string safe_label(const std::string& name) {
  std::string out;
  for (const char ch : name.substr(0, 64)) {
    const bool ok = std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-';
    out.push_back(ok ? ch : '_');
  }
  return out.empty() ? std::string("mesh") : out;
}

std::string file_stem(const std::string& name) {
  std::string stem = safe_label(name);
  if (const std::size_t dot = stem.rfind('.'); dot != std::string::npos && dot > 0) stem.resize(dot);
  return stem;
}

std::string lower_extension(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  std::string ext = dot == std::string::npos ? std::string() : name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return ext;
}

} // namespace iarap::serve
