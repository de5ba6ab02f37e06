// A folder only this process can read (mkdtemp, mode 0700) for the files the server must write itself:
// uploaded meshes handed to read_mesh, and meshes written by write_mesh for download. Removed with its
// contents when destroyed. File names come from a counter, never from the client.
#pragma once
#include <atomic>
#include <filesystem>
#include <string>

namespace iarap::serve {

class PrivateTempDir {
public:
  PrivateTempDir(); // throws iarap::Error naming the system's reason
  ~PrivateTempDir();
  PrivateTempDir(const PrivateTempDir&) = delete;
  PrivateTempDir& operator=(const PrivateTempDir&) = delete;

  // A fresh path "<dir>/<stem>-<n>.<extension>" no other call returns (safe across threads).
  std::filesystem::path unique_path(const std::string& stem, const std::string& extension);

private:
  std::filesystem::path path_;
  std::atomic<unsigned long> counter_{0};
};

// Removes a file when it goes out of scope, whatever happened in between.
class ScopedFile {
public:
  explicit ScopedFile(std::filesystem::path path) : path_(std::move(path)) {}
  ~ScopedFile();
  ScopedFile(const ScopedFile&) = delete;
  ScopedFile& operator=(const ScopedFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

private:
  std::filesystem::path path_;
};

} // namespace iarap::serve
