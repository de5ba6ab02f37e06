// Hand-written: Debian has no C/C++ PLY library (rply, happly, tinyply are not packaged) and the format
// needs exact errors, all three encodings, arbitrary list types and the `tristrips` element.
#include "iarap/io/read_mesh.h"
#include "ply_format.h"

namespace iarap {

MeshData read_ply(const std::string& path) {
  using namespace io_detail;
  const std::string text = read_whole_file(path);
  LineReader lines(text, utf8_bom_length(text));
  const PlyHeader header = read_ply_header(path, lines);
  const bool ascii = header.encoding == PlyEncoding::ascii;
  PlyBody body(path, ascii ? Location::line : Location::byte_offset);
  if (ascii)
    read_ply_ascii_body(path, header, lines, body);
  else
    read_ply_binary_body(path, header, text, lines.offset(), body);
  MeshData mesh;
  mesh.F = body.faces.finish(body.num_vertices, mesh.notes);
  mesh.V = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(body.positions.data(),
                                                                                       body.num_vertices, 3);
  return mesh;
}

} // namespace iarap
