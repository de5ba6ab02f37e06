#include "iarap/param/write_uv_map.h"

#include "../io/atomic_file.h"
#include "../io/file_extension.h"
#include "../io/writer_support.h"

#include "iarap/core/errors.h"

namespace iarap {

namespace {

void append_uv_lines(std::string& out, const Eigen::MatrixXd& UV, const char* prefix) {
  for (Eigen::Index v = 0; v < UV.rows(); ++v) {
    out += prefix;
    io_detail::append_double(out, UV(v, 0));
    out += ' ';
    io_detail::append_double(out, UV(v, 1));
    out += '\n';
  }
}

// `f a/a b/b c/c`: vertex and texture coordinate share their index, counted from 1.
void append_textured_faces(std::string& out, const Eigen::MatrixXi& F) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      io_detail::append_int(out, F(f, k) + 1LL);
      out += '/';
      io_detail::append_int(out, F(f, k) + 1LL);
    }
    out += '\n';
  }
}

} // namespace

void write_uv_map(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                  const Eigen::MatrixXd& UV) {
  const std::string extension = io_detail::lower_extension(path);
  if (extension != ".obj" && extension != ".txt")
    throw InputError(path + ": cannot write a UV map as '" + extension +
                     "'; use .obj (mesh with vt) or .txt (u v)");
  io_detail::check_mesh_arrays(path, V, F);
  if (UV.rows() != V.rows() || UV.cols() != 2)
    throw InputError(path + ": UV must be #V x 2 = " + std::to_string(V.rows()) + " x 2; got " +
                     std::to_string(UV.rows()) + " x " + std::to_string(UV.cols()));
  std::string out;
  if (extension == ".txt") {
    out.reserve(static_cast<std::size_t>(UV.rows() * 48));
    append_uv_lines(out, UV, "");
  } else {
    out.reserve(static_cast<std::size_t>(V.rows() * 110 + F.rows() * 48));
    out += "# UV map written by iarap\n";
    io_detail::append_vertex_lines(out, V, "v ");
    append_uv_lines(out, UV, "vt ");
    append_textured_faces(out, F);
  }
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
