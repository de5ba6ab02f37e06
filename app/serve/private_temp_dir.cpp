#include "private_temp_dir.h"

#include "iarap/core/errors.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace iarap::serve {

PrivateTempDir::PrivateTempDir() {
  std::error_code error;
  std::filesystem::path base = std::filesystem::temp_directory_path(error);
  if (error) base = "/tmp";
  std::string pattern = (base / "iarap-serve-XXXXXX").string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr)
    throw Error("cannot create a private temporary folder under " + base.string() + ": " +
                std::strerror(errno));
  path_ = buffer.data();
}

PrivateTempDir::~PrivateTempDir() {
  std::error_code error; // nothing useful to do with a failure while shutting down
  std::filesystem::remove_all(path_, error);
}

std::filesystem::path PrivateTempDir::unique_path(const std::string& stem, const std::string& extension) {
  const unsigned long n = counter_.fetch_add(1);
  return path_ / (stem + "-" + std::to_string(n) + "." + extension);
}

ScopedFile::~ScopedFile() {
  std::error_code error;
  std::filesystem::remove(path_, error);
}

} // namespace iarap::serve
