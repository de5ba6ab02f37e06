#include "atomic_file.h"
#include "iarap/io/write_mesh.h"
#include "writer_support.h"

namespace iarap {

void write_off(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  io_detail::check_mesh_arrays(path, V, F);
  std::string out;
  out.reserve(static_cast<std::size_t>(V.rows() * 60 + F.rows() * 24));
  out += "OFF\n";
  io_detail::append_int(out, V.rows());
  out += ' ';
  io_detail::append_int(out, F.rows());
  out += " 0\n";
  io_detail::append_vertex_lines(out, V, "");
  io_detail::append_face_lines(out, F, "3 ", 0);
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
