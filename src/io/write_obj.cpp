#include "atomic_file.h"
#include "iarap/io/write_mesh.h"
#include "writer_support.h"

namespace iarap {

void write_obj(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  io_detail::check_mesh_arrays(path, V, F);
  std::string out;
  out.reserve(static_cast<std::size_t>(V.rows() * 60 + F.rows() * 24));
  out += "# written by iarap\n";
  io_detail::append_vertex_lines(out, V, "v ");
  io_detail::append_face_lines(out, F, "f ", 1); // OBJ counts from 1
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
