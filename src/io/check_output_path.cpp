#include "iarap/io/check_output_path.h"

#include "file_extension.h"
#include "iarap/core/errors.h"

#include <filesystem>
#include <unistd.h>

namespace iarap {

void check_output_path(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) throw InputError("output path is empty");
  const fs::path target(path);
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  std::error_code error;
  if (fs::is_directory(target, error))
    throw InputError(path + ": is a folder; give a file name for the output");
  if (!fs::exists(folder, error))
    throw InputError(path + ": the folder " + folder.string() + " does not exist; create it first");
  if (!fs::is_directory(folder, error)) throw InputError(path + ": " + folder.string() + " is not a folder");
  // The atomic writers create a temporary file beside the target: the folder must be writable.
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError(path + ": the folder " + folder.string() + " is not writable");
}

void check_mesh_output_path(const std::string& path) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply")
    throw InputError(path + ": unsupported mesh extension '" + ext +
                     "' for writing (writable: .obj .off .ply)");
  check_output_path(path);
}

} // namespace iarap
