// TetGen's .node / .ele pair (https://wias-berlin.de/software/tetgen/fformats.html).
#include "iarap/io/read_tet_mesh.h"

#include "iarap/core/errors.h"

#include "file_extension.h"
#include "read_tet_mesh_support.h"

#include <filesystem>

namespace iarap {

namespace {

// The .node file: positions into parse; returns the file's first index (0 or 1).
int read_node_file(const std::string& path, io_detail::TetParse& parse) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::TokenLines in(path, text, true);
  std::vector<std::string_view> tokens;
  in.require(tokens, "the header '#points 3 #attributes #markers'");
  const std::int64_t n = io_detail::parse_count(path, in.line(), tokens[0], "point count");
  if (tokens.size() > 1 && io_detail::parse_count(path, in.line(), tokens[1], "dimension", 2, 3) != 3)
    io_detail::fail_at_line(path, in.line(), "dimension 2: a tetrahedral mesh needs dimension 3");
  int base = 0;
  for (std::int64_t v = 0; v < n; ++v) {
    in.require(tokens, "point " + std::to_string(v) + " of " + std::to_string(n));
    if (tokens.size() < 4)
      io_detail::fail_at_line(path, in.line(),
                              "expected 'index x y z', got " + std::to_string(tokens.size()) + " tokens");
    const std::int64_t index = io_detail::parse_count(path, in.line(), tokens[0], "point index", -2147483647);
    if (v == 0) {
      if (index != 0 && index != 1)
        io_detail::fail_at_line(path, in.line(),
                                "the first point index is " + std::to_string(index) +
                                    "; TetGen numbers points from 0 or 1");
      base = static_cast<int>(index);
    } else if (index != base + v) {
      io_detail::fail_at_line(path, in.line(),
                              "point index " + std::to_string(index) + " where " + std::to_string(base + v) +
                                  " was expected (points are numbered consecutively)");
    }
    double x[3];
    for (int c = 0; c < 3; ++c)
      x[c] = io_detail::parse_coordinate(path, in.line(), tokens[static_cast<size_t>(c) + 1], "coordinate");
    parse.add_vertex(x[0], x[1], x[2]);
  }
  return base;
}

void read_ele_file(const std::string& path, int base, io_detail::TetParse& parse) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::TokenLines in(path, text, true);
  std::vector<std::string_view> tokens;
  in.require(tokens, "the header '#tetrahedra 4|10 #attributes'");
  const std::int64_t m = io_detail::parse_count(path, in.line(), tokens[0], "tetrahedron count");
  std::int64_t corners = 4;
  if (tokens.size() > 1)
    corners = io_detail::parse_count(path, in.line(), tokens[1], "nodes per tetrahedron", 4, 10);
  if (corners != 4 && corners != 10)
    io_detail::fail_at_line(path, in.line(),
                            "nodes per tetrahedron must be 4 or 10, got " + std::to_string(corners));
  if (corners == 10)
    parse.notes.push_back("kept the 4 corners of " + std::to_string(m) + " quadratic tetrahedra");
  for (std::int64_t t = 0; t < m; ++t) {
    in.require(tokens, "tetrahedron " + std::to_string(t) + " of " + std::to_string(m));
    if (tokens.size() < 5)
      io_detail::fail_at_line(path, in.line(),
                              "expected 'index a b c d', got " + std::to_string(tokens.size()) + " tokens");
    io_detail::parse_count(path, in.line(), tokens[0], "tetrahedron index", -2147483647);
    for (int k = 1; k <= 4; ++k)
      parse.tets.push_back(io_detail::parse_count(path, in.line(), tokens[static_cast<size_t>(k)],
                                                  "vertex index", -2147483647) -
                           base);
    parse.tet_line.push_back(in.line());
  }
}

} // namespace

TetMesh read_tetgen(const std::string& path) {
  std::filesystem::path stem(path);
  const std::string ext = io_detail::lower_extension(path);
  if (ext != ".node" && ext != ".ele") throw InputError(path + ": a TetGen mesh is a .node or .ele file");
  const std::string node = stem.replace_extension(".node").string(),
                    ele = stem.replace_extension(".ele").string();
  io_detail::TetParse parse;
  const int base = read_node_file(node, parse);
  read_ele_file(ele, base, parse);
  // Out-of-range indices and bad tetrahedra are named in the .ele file.
  return io_detail::finish_tet_mesh(ele, std::move(parse), base);
}

} // namespace iarap
