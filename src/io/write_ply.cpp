#include "atomic_file.h"
#include "iarap/io/write_mesh.h"
#include "writer_support.h"

#include <cstdint>
#include <cstring>

namespace iarap {

namespace {

// Appends the little-endian bytes of a trivially copyable value, whatever the host's byte order.
template <typename T> void append_little_endian(std::string& out, T value) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  if (first != 1)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

} // namespace

void write_ply(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               PlyEncoding encoding) {
  io_detail::check_mesh_arrays(path, V, F);
  const bool ascii = encoding == PlyEncoding::ascii;
  std::string out;
  out.reserve(static_cast<std::size_t>(V.rows() * 60 + F.rows() * 24 + 256));
  out += "ply\nformat ";
  out += ascii ? "ascii" : "binary_little_endian";
  out += " 1.0\ncomment written by iarap\nelement vertex ";
  io_detail::append_int(out, V.rows());
  out += "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  io_detail::append_int(out, F.rows());
  out += "\nproperty list uchar int vertex_indices\nend_header\n";
  if (ascii) {
    io_detail::append_vertex_lines(out, V, "");
    io_detail::append_face_lines(out, F, "3 ", 0);
  } else {
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      for (int k = 0; k < 3; ++k) append_little_endian(out, V(v, k));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      append_little_endian(out, static_cast<std::uint8_t>(3));
      for (int k = 0; k < 3; ++k) append_little_endian(out, static_cast<std::int32_t>(F(f, k)));
    }
  }
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
