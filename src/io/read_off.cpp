// Hand-written: no Debian library reads OFF with line-numbered errors; the format is a few lines of rules.
#include "face_builder.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "text_reader.h"

#include <algorithm>
#include <utility>

namespace iarap {

using io_detail::fail_at_line;
using io_detail::quote_token;

namespace {

// Next line with content, skipping blank lines and '#' comments; false at the end of the text.
bool next_content_line(io_detail::LineReader& lines, std::vector<std::string_view>& tokens) {
  std::string_view line;
  while (lines.next(line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    io_detail::split_tokens(line, tokens);
    if (!tokens.empty()) return true;
  }
  return false;
}

// The keyword [ST][C][N][4][n]OFF, optionally followed on the same line by the counts of vertices, faces
// and edges (the edge count is ignored), which may continue on following lines. Returns {#V, #F}.
std::pair<std::int64_t, std::int64_t> read_off_header(const std::string& path, io_detail::LineReader& lines,
                                                      std::vector<std::string_view>& tokens) {
  if (!next_content_line(lines, tokens))
    fail_at_line(path, lines.line(), "empty file; expected an OFF header");
  const std::string_view keyword = tokens[0];
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    fail_at_line(path, lines.line(), "expected the keyword OFF, found " + quote_token(keyword));
  const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  if (prefix.find_first_not_of("STCN") != std::string_view::npos)
    fail_at_line(path, lines.line(),
                 "unsupported OFF variant " + quote_token(keyword) + " (only 3D [ST][C][N]OFF)");
  std::size_t next_token = 1;
  if (tokens.size() > 1 && tokens[1] == "BINARY")
    fail_at_line(path, lines.line(), "binary OFF is not supported; convert it to ASCII OFF or PLY");

  std::int64_t counts[3];
  int have = 0;
  while (have < 3) {
    if (next_token >= tokens.size()) {
      if (!next_content_line(lines, tokens))
        fail_at_line(path, lines.line(),
                     "file ends inside the header; expected vertex, face and edge counts");
      next_token = 0;
    }
    if (!io_detail::parse_int(tokens[next_token], counts[have]) || counts[have] < 0)
      fail_at_line(path, lines.line(), "bad count " + quote_token(tokens[next_token]) + " in the header");
    ++next_token;
    ++have;
  }
  if (next_token < tokens.size())
    fail_at_line(path, lines.line(),
                 "unexpected " + quote_token(tokens[next_token]) + " after the header counts");
  return {counts[0], counts[1]};
}

// nv vertex records, x y z each (further values, such as colors, are ignored), appended to positions.
void read_off_vertices(const std::string& path, io_detail::LineReader& lines,
                       std::vector<std::string_view>& tokens, std::int64_t nv,
                       std::vector<double>& positions) {
  for (std::int64_t v = 0; v < nv; ++v) {
    if (!next_content_line(lines, tokens))
      fail_at_line(path, lines.line(),
                   "file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    if (tokens.size() < 3)
      fail_at_line(path, lines.line(),
                   "vertex " + std::to_string(v) + " needs 3 coordinates, found " +
                       std::to_string(tokens.size()));
    for (int k = 0; k < 3; ++k) {
      double x;
      if (!io_detail::parse_double(tokens[static_cast<std::size_t>(k)], x))
        fail_at_line(path, lines.line(),
                     "vertex " + std::to_string(v) + ": bad coordinate " +
                         quote_token(tokens[static_cast<std::size_t>(k)]));
      positions.push_back(x);
    }
  }
}

// The corner indices of face f, whose record starts in tokens (its corner count first). A record may
// continue on the following lines (valid OFF; libigl's test data has such files); values past the n indices
// on its last line are a per-face color, which is allowed and ignored.
void read_off_face(const std::string& path, io_detail::LineReader& lines,
                   std::vector<std::string_view>& tokens, std::int64_t f,
                   std::vector<std::int64_t>& corners) {
  std::int64_t n;
  if (!io_detail::parse_int(tokens[0], n) || n < 0)
    fail_at_line(path, lines.line(),
                 "face " + std::to_string(f) + ": bad corner count " + quote_token(tokens[0]));
  const std::int64_t face_line = lines.line();
  corners.clear();
  std::size_t next = 1;
  while (static_cast<std::int64_t>(corners.size()) < n) {
    if (next >= tokens.size()) {
      if (!next_content_line(lines, tokens))
        fail_at_line(path, face_line,
                     "face " + std::to_string(f) + " declares " + std::to_string(n) +
                         " corners but the file ends after " + std::to_string(corners.size()));
      next = 0;
    }
    const std::string_view token = tokens[next++];
    std::int64_t index;
    if (!io_detail::parse_int(token, index))
      fail_at_line(path, lines.line(),
                   "face " + std::to_string(f) + ": bad vertex index " + quote_token(token) + " (face " +
                       std::to_string(f) + " declares " + std::to_string(n) + " corners and starts on line " +
                       std::to_string(face_line) + ")");
    corners.push_back(index);
  }
}

} // namespace

MeshData read_off(const std::string& path) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::LineReader lines(text, io_detail::utf8_bom_length(text));
  std::vector<std::string_view> tokens;
  const auto [nv, nf] = read_off_header(path, lines, tokens);

  // Each record takes at least 2 bytes ("x\n"), so the remaining size caps any honest count; reserve no more.
  const std::int64_t cap = static_cast<std::int64_t>(lines.remaining_bytes() / 2);
  std::vector<double> positions;
  positions.reserve(static_cast<std::size_t>(3 * std::min(nv, cap)));
  read_off_vertices(path, lines, tokens, nv, positions);

  io_detail::FaceBuilder faces(path, io_detail::Location::line);
  faces.reserve_triangles(static_cast<std::size_t>(std::min(nf, cap)));
  std::vector<std::int64_t> corners;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_content_line(lines, tokens))
      fail_at_line(path, lines.line(),
                   "file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::int64_t face_line = lines.line();
    read_off_face(path, lines, tokens, f, corners);
    faces.add_polygon(corners, face_line);
  }
  if (next_content_line(lines, tokens))
    fail_at_line(path, lines.line(),
                 "unexpected data after the " + std::to_string(nf) + " faces the header declares");

  MeshData mesh;
  mesh.F = faces.finish(nv, mesh.notes);
  mesh.V =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(positions.data(), nv, 3);
  return mesh;
}

} // namespace iarap
