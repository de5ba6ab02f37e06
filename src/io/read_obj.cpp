// Hand-written rather than tinyobjloader (installed): its number parser silently turns a bad token into 0,
// it parses indices with atoi (so "3x" reads as 3), and reports out-of-range indices only as a warning
// carrying the last line of the file, so it cannot give the exact "path:line" errors this reader promises.
#include "face_builder.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/read_obj_textured.h"
#include "text_reader.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace iarap {

using io_detail::fail_at_line;
using io_detail::quote_token;

namespace {

// The texture side of read_obj_textured, collected while the positions and faces are read.
struct TextureLines {
  std::vector<double> uv;           // 2 per vt line
  std::vector<std::int64_t> corner; // per polygon corner: 0-based vt index, -1 none
  std::vector<int> first{0};        // per polygon: offset into corner (and the polygon's vertices)
  std::vector<int> vertex;          // per polygon corner: 0-based vertex index
  std::int64_t max_index = -1, max_line = 0, max_polygon = 0; // the largest vt index used, where
};

void read_texture_line(const std::string& path, std::int64_t line,
                       const std::vector<std::string_view>& tokens, TextureLines& texture) {
  // vt u [v [w]]: a missing v is 0 (the OBJ specification), w is dropped.
  if (tokens.size() < 2) fail_at_line(path, line, "texture coordinate needs at least u");
  for (std::size_t k = 1; k <= 2; ++k) {
    double x = 0;
    if (k < tokens.size() && !io_detail::parse_double(tokens[k], x))
      fail_at_line(path, line, "bad texture coordinate " + quote_token(tokens[k]));
    texture.uv.push_back(x);
  }
}

// The t of a corner i/t or i/t/n (-1 for i and i//n), absolute and 0-based.
std::int64_t texture_index(const std::string& path, std::int64_t line, std::int64_t polygon,
                           std::string_view corner, TextureLines& texture) {
  const std::size_t slash = corner.find('/');
  if (slash == std::string_view::npos) return -1;
  const std::string_view rest = corner.substr(slash + 1);
  const std::string_view token = rest.substr(0, rest.find('/'));
  if (token.empty()) return -1;
  std::int64_t index;
  if (!io_detail::parse_int(token, index))
    fail_at_line(path, line,
                 "face " + std::to_string(polygon) + ": bad texture index " + quote_token(corner));
  if (index == 0)
    fail_at_line(path, line,
                 "face " + std::to_string(polygon) + " uses texture index 0 (OBJ indices start at 1)");
  const auto defined = static_cast<std::int64_t>(texture.uv.size() / 2);
  if (index < 0) {
    if (-index > defined)
      fail_at_line(path, line,
                   "face " + std::to_string(polygon) + " uses relative texture index " +
                       std::to_string(index) + " but only " + std::to_string(defined) +
                       " texture coordinates are defined before it");
    return defined + index;
  }
  if (index - 1 > texture.max_index) {
    texture.max_index = index - 1;
    texture.max_line = line;
    texture.max_polygon = polygon;
  }
  return index - 1;
}

// read_obj's parser; with `texture` it also keeps the vt lines, corners' texture indices and the polygons.
MeshData parse_obj(const std::string& path, TextureLines* texture) {
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
        if (texture) texture->corner.push_back(texture_index(path, lines.line(), polygon, corner, *texture));
      }
      if (texture) {
        const auto first = static_cast<std::size_t>(texture->first.back());
        const auto untextured = std::count(texture->corner.begin() + static_cast<std::ptrdiff_t>(first),
                                           texture->corner.end(), std::int64_t{-1});
        if (untextured > 0 && untextured < static_cast<std::ptrdiff_t>(corners.size()))
          fail_at_line(path, lines.line(),
                       "face " + std::to_string(polygon) +
                           " has texture indices on some corners only (i/t on every corner, or on none)");
        for (std::int64_t c : corners)
          texture->vertex.push_back(
              static_cast<int>(std::min<std::int64_t>(c, std::numeric_limits<int>::max())));
        texture->first.push_back(static_cast<int>(texture->corner.size()));
      }
      faces.add_polygon(corners, lines.line());
      ++polygon;
    } else if (keyword == "vt" && texture) {
      read_texture_line(path, lines.line(), tokens, *texture);
    }
    // vt (for read_obj), vn, vp, g, o, s, usemtl, mtllib, l, p and unknown statements carry nothing ARAP
    // uses.
  }
  MeshData mesh;
  const std::int64_t nv = static_cast<std::int64_t>(positions.size() / 3);
  mesh.F = faces.finish(nv, mesh.notes);
  mesh.V =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(positions.data(), nv, 3);
  return mesh;
}

} // namespace

MeshData read_obj(const std::string& path) {
  return parse_obj(path, nullptr);
}

TexturedObj read_obj_textured(const std::string& path) {
  TextureLines texture;
  TexturedObj obj;
  obj.mesh = parse_obj(path, &texture);
  const auto count = static_cast<std::int64_t>(texture.uv.size() / 2);
  if (texture.max_index >= count)
    fail_at_line(path, texture.max_line,
                 "face " + std::to_string(texture.max_polygon) + " uses texture index " +
                     std::to_string(texture.max_index + 1) + " but the file has " + std::to_string(count) +
                     " texture coordinates (vt lines)");
  obj.TC = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(texture.uv.data(),
                                                                                       count, 2);
  obj.polygons.first = std::move(texture.first);
  obj.polygons.vertex = std::move(texture.vertex);
  obj.polygons.texture.assign(texture.corner.begin(), texture.corner.end());
  // The fan of FaceBuilder::add_polygon: triangles (c0, ci, ci+1), i = 1 .. n - 2, polygon after polygon.
  obj.FT.resize(obj.mesh.F.rows(), 3);
  obj.polygon_of_triangle.reserve(static_cast<std::size_t>(obj.mesh.F.rows()));
  Eigen::Index t = 0;
  for (int p = 0; p < obj.polygons.size(); ++p) {
    const int* corner = obj.polygons.texture.data() + obj.polygons.first[static_cast<std::size_t>(p)];
    for (int i = 1; i + 1 < obj.polygons.corners(p); ++i, ++t) {
      obj.FT.row(t) << corner[0], corner[i], corner[i + 1];
      obj.polygon_of_triangle.push_back(p);
    }
  }
  return obj;
}

} // namespace iarap
