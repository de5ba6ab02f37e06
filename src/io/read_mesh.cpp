#include "iarap/io/read_mesh.h"

#include "file_extension.h"
#include "iarap/core/errors.h"

namespace iarap {

MeshData read_mesh(const std::string& path) {
  const std::string ext = io_detail::lower_extension(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".off") return read_off(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".stl") return read_stl(path);
  throw InputError(path + ": unsupported mesh extension '" + ext + "' (readable: .obj .off .ply .stl)");
}

} // namespace iarap
