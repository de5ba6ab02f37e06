// Hand-written: no Debian library reads STL into indexed meshes with located errors. STL stores each triangle
// with its own three corners, so this is the one reader that renumbers: bitwise identical positions are
// welded.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "text_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

namespace iarap {

using io_detail::fail_at_line;
using io_detail::fail_at_offset;
using io_detail::quote_token;

namespace {

// Welds identical corner positions (-0 and +0 count as equal; NaN never equals itself, so stays apart).
// corners: 3 doubles per triangle corner. Vertices are numbered by first appearance; O(n log n).
MeshData weld_corners(const std::vector<double>& corners) {
  const std::size_t n = corners.size() / 3;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto key = [&](std::size_t i, int k) {
    const double x = corners[3 * i + static_cast<std::size_t>(k)];
    return x == 0.0 ? 0.0 : x; // -0 -> +0
  };
  // NaN sorts after every number so the order stays strict and weak; NaN corners never weld (== fails).
  const auto less = [&](std::size_t a, std::size_t b) {
    for (int k = 0; k < 3; ++k) {
      const double x = key(a, k), y = key(b, k);
      const bool xn = std::isnan(x), yn = std::isnan(y);
      if (xn != yn) return yn;
      if (xn) continue;
      if (x < y) return true;
      if (y < x) return false;
    }
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  // representative[i]: the first corner (smallest index) at corner i's position.
  std::vector<std::size_t> representative(n);
  for (std::size_t s = 0; s < n; ++s) {
    const std::size_t i = order[s];
    const std::size_t prev = s > 0 ? order[s - 1] : i;
    const bool same =
        s > 0 && key(i, 0) == key(prev, 0) && key(i, 1) == key(prev, 1) && key(i, 2) == key(prev, 2);
    representative[i] = same ? representative[prev] : i;
  }
  std::vector<int> vertex_of(n, -1);
  std::vector<double> positions;
  MeshData mesh;
  mesh.F.resize(static_cast<Eigen::Index>(n / 3), 3);
  int nv = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = representative[i];
    if (vertex_of[r] < 0) {
      vertex_of[r] = nv++;
      positions.insert(positions.end(), corners.begin() + static_cast<std::ptrdiff_t>(3 * r),
                       corners.begin() + static_cast<std::ptrdiff_t>(3 * r + 3));
    }
    mesh.F(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)) = vertex_of[r];
  }
  mesh.V =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(positions.data(), nv, 3);
  mesh.notes.push_back("welded " + std::to_string(n) + " STL triangle corners into " + std::to_string(nv) +
                       " vertices with identical positions (vertices renumbered by first appearance)");
  return mesh;
}

std::vector<double> read_binary_corners(const std::string& bytes, std::uint32_t count) {
  std::vector<double> corners;
  corners.reserve(static_cast<std::size_t>(count) * 9); // size already checked against the file
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::size_t record = 84 + 50 * static_cast<std::size_t>(t);
    for (int k = 0; k < 9; ++k) { // skip the 12-byte normal; 3 corners x 3 little-endian float32
      unsigned char b[4];
      std::memcpy(b, bytes.data() + record + 12 + 4 * static_cast<std::size_t>(k), 4);
      const std::uint32_t u = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                              static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
      float f;
      std::memcpy(&f, &u, 4);
      corners.push_back(static_cast<double>(f));
    }
  }
  return corners;
}

std::vector<double> read_ascii_corners(const std::string& path, const std::string& text) {
  io_detail::LineReader lines(text, io_detail::utf8_bom_length(text));
  std::vector<std::string_view> tokens;
  std::string_view line;
  std::vector<double> corners;
  std::vector<double> loop; // corners of the current facet
  enum class State { solid, facet, in_loop, after_loop, done } state = State::solid;
  bool started = false;
  std::int64_t facet = 0;
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty()) continue;
    const std::string_view w = tokens[0];
    const auto expect = [&](const char* what) {
      fail_at_line(path, lines.line(), std::string("expected ") + what + ", found " + quote_token(w));
    };
    if (!started) {
      if (w != "solid") expect("'solid'");
      started = true;
      continue;
    }
    switch (state) {
    case State::solid:
      if (w == "endsolid")
        state = State::done;
      else if (w == "facet")
        state = State::facet;
      else
        expect("'facet' or 'endsolid'");
      break;
    case State::facet:
      if (w != "outer" || tokens.size() < 2 || tokens[1] != "loop") expect("'outer loop'");
      loop.clear();
      state = State::in_loop;
      break;
    case State::in_loop:
      if (w == "endloop") {
        if (loop.size() < 9)
          fail_at_line(path, lines.line(),
                       "facet " + std::to_string(facet) + " has " + std::to_string(loop.size() / 3) +
                           " vertices; at least 3 needed");
        // Polygons (rare) are fanned from the first corner like the other readers do.
        for (std::size_t i = 1; i + 1 < loop.size() / 3; ++i) {
          corners.insert(corners.end(), loop.begin(), loop.begin() + 3);
          corners.insert(corners.end(), loop.begin() + static_cast<std::ptrdiff_t>(3 * i),
                         loop.begin() + static_cast<std::ptrdiff_t>(3 * i + 6));
        }
        state = State::after_loop;
      } else if (w == "vertex") {
        if (tokens.size() != 4)
          fail_at_line(path, lines.line(), "facet " + std::to_string(facet) + ": vertex needs 3 coordinates");
        for (int k = 1; k <= 3; ++k) {
          double x;
          if (!io_detail::parse_double(tokens[static_cast<std::size_t>(k)], x))
            fail_at_line(path, lines.line(),
                         "facet " + std::to_string(facet) + ": bad coordinate " +
                             quote_token(tokens[static_cast<std::size_t>(k)]));
          loop.push_back(x);
        }
      } else {
        expect("'vertex' or 'endloop'");
      }
      break;
    case State::after_loop:
      if (w != "endfacet") expect("'endfacet'");
      ++facet;
      state = State::solid;
      break;
    case State::done:
      // Some files hold several solids back to back.
      if (w != "solid") expect("end of file or another 'solid'");
      state = State::solid;
      break;
    }
  }
  if (!started) fail_at_line(path, lines.line(), "empty file");
  if (state != State::done) fail_at_line(path, lines.line(), "file ends inside a solid (no 'endsolid')");
  return corners;
}

} // namespace

MeshData read_stl(const std::string& path) {
  const std::string bytes = io_detail::read_whole_file(path);
  bool binary = false;
  std::uint32_t count = 0;
  if (bytes.size() >= 84) {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data()) + 80;
    count = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
            static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
    // Binary files may also start with "solid"; the exact size decides.
    binary = bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
  }
  const bool looks_ascii = bytes.compare(io_detail::utf8_bom_length(bytes), 5, "solid") == 0;
  if (!binary && !looks_ascii) {
    if (bytes.size() < 84)
      fail_at_offset(path, static_cast<std::int64_t>(bytes.size()),
                     "file too short for a binary STL (84-byte header) and does not start with 'solid'");
    fail_at_offset(path, 80,
                   "binary STL declares " + std::to_string(count) + " triangles, which need " +
                       std::to_string(84 + 50 * static_cast<std::uint64_t>(count)) +
                       " bytes, but the file has " + std::to_string(bytes.size()));
  }
  const std::vector<double> corners =
      binary ? read_binary_corners(bytes, count) : read_ascii_corners(path, bytes);
  return weld_corners(corners);
}

} // namespace iarap
