#include "iarap/io/write_mesh.h"

#include "file_extension.h"
#include "iarap/core/errors.h"

namespace iarap {

void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext == ".obj") return write_obj(path, V, F);
  if (ext == ".off") return write_off(path, V, F);
  if (ext == ".ply") return write_ply(path, V, F);
  throw InputError(path + ": unsupported mesh extension '" + ext +
                   "' for writing (writable: .obj .off .ply)");
}

} // namespace iarap
