// Hand-written rather than tinyobjloader (installed): its number parser silently turns a bad token into 0,
// it parses indices with atoi (so "3x" reads as 3), and reports out-of-range indices only as a warning
// carrying the last line of the file, so it cannot give the exact "path:line" errors this reader promises.
#include "face_builder.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "text_reader.h"

namespace iarap {

using io_detail::fail_at_line;
using io_detail::quote_token;

MeshData read_obj(const std::string& path) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::LineReader lines(text, io_detail::utf8_bom_length(text));
  io_detail::FaceBuilder faces(path, io_detail::Location::line, 1);
  std::vector<double> positions;
  std::vector<std::string_view> tokens;
  std::vector<std::int64_t> corners;
  std::int64_t polygon = 0;
  std::string_view line;
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty() || tokens[0][0] == '#') continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "v") {
      // v x y z [w] (and some exporters append r g b): the first three numbers are the position.
      if (tokens.size() < 4)
        fail_at_line(path, lines.line(),
                     "vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
      for (int k = 1; k <= 3; ++k) {
        double x;
        if (!io_detail::parse_double(tokens[static_cast<std::size_t>(k)], x))
          fail_at_line(path, lines.line(),
                       "bad vertex coordinate " + quote_token(tokens[static_cast<std::size_t>(k)]));
        positions.push_back(x);
      }
    } else if (keyword == "f") {
      corners.clear();
      const std::int64_t defined = static_cast<std::int64_t>(positions.size() / 3);
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view corner = tokens[k];
        if (corner[0] == '#') break; // trailing comment
        // i, i/t, i//n, i/t/n: only the position index matters here.
        const std::string_view index_token = corner.substr(0, corner.find('/'));
        std::int64_t index;
        if (!io_detail::parse_int(index_token, index))
          fail_at_line(path, lines.line(),
                       "face " + std::to_string(polygon) + ": bad vertex index " + quote_token(corner));
        if (index == 0)
          fail_at_line(path, lines.line(),
                       "face " + std::to_string(polygon) + " uses vertex index 0 (OBJ indices start at 1)");
        if (index < 0) {
          // Relative index: -1 is the last vertex defined so far.
          if (-index > defined)
            fail_at_line(path, lines.line(),
                         "face " + std::to_string(polygon) + " uses relative vertex index " +
                             std::to_string(index) + " but only " + std::to_string(defined) +
                             " vertices are defined before it");
          corners.push_back(defined + index);
        } else {
          corners.push_back(index - 1);
        }
      }
      faces.add_polygon(corners, lines.line());
      ++polygon;
    }
    // vt, vn, vp, g, o, s, usemtl, mtllib, l, p and unknown statements carry nothing ARAP uses.
  }
  MeshData mesh;
  const std::int64_t nv = static_cast<std::int64_t>(positions.size() / 3);
  mesh.F = faces.finish(nv, mesh.notes);
  mesh.V =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(positions.data(), nv, 3);
  return mesh;
}

} // namespace iarap
