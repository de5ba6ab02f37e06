// MEDIT's ASCII .mesh (the INRIA format that TetGen, CGAL, MMG and fTetWild write), read here by hand: the
// libMeshb library is not packaged for Debian, and the subset a tet mesh needs is a few keywords.
#include "iarap/io/read_tet_mesh.h"

#include "read_tet_mesh_support.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace iarap {

namespace {

std::string lower(std::string_view token) {
  std::string out(token);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// Tokens per entry of the sections read past (after their count).
int skipped_entry_tokens(const std::string& keyword) {
  static const std::pair<const char*, int> sections[] = {{"edges", 3},
                                                         {"triangles", 4},
                                                         {"quadrilaterals", 5},
                                                         {"hexahedra", 9},
                                                         {"prisms", 7},
                                                         {"pyramids", 6},
                                                         {"corners", 1},
                                                         {"requiredvertices", 1},
                                                         {"ridges", 1},
                                                         {"requirededges", 1},
                                                         {"requiredtriangles", 1},
                                                         {"requiredquadrilaterals", 1},
                                                         {"normals", 3},
                                                         {"tangents", 3},
                                                         {"normalatvertices", 2},
                                                         {"tangentatvertices", 2},
                                                         {"normalattrianglevertices", 3},
                                                         {"tangentatedges", 3},
                                                         {"edgesp2", 4},
                                                         {"trianglesp2", 7},
                                                         {"tetrahedrap2", 11}};
  for (const auto& [name, tokens] : sections)
    if (keyword == name) return tokens;
  return 0;
}

} // namespace

TetMesh read_medit_mesh(const std::string& path) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::TokenStream in(path, text, true);
  io_detail::TetParse parse;
  bool vertices = false, tetrahedra = false;
  std::string_view token;
  while (in.next(token)) {
    const std::string keyword = lower(token);
    const std::int64_t line = in.line();
    if (keyword == "end") break;
    if (keyword == "meshversionformatted") {
      io_detail::parse_count(path, in.line(), in.require("a version"), "version", 1, 4);
    } else if (keyword == "dimension") {
      const std::int64_t d =
          io_detail::parse_count(path, in.line(), in.require("a dimension"), "dimension", 2, 3);
      if (d != 3)
        io_detail::fail_at_line(path, in.line(), "Dimension 2: a tetrahedral mesh needs Dimension 3");
    } else if (keyword == "vertices") {
      const std::int64_t n =
          io_detail::parse_count(path, in.line(), in.require("a vertex count"), "vertex count");
      for (std::int64_t v = 0; v < n; ++v) {
        double x[3];
        for (double& c : x)
          c = io_detail::parse_coordinate(path, in.line(), in.require("vertex " + std::to_string(v + 1)),
                                          "coordinate");
        io_detail::parse_count(path, in.line(),
                               in.require("the reference of vertex " + std::to_string(v + 1)), "reference",
                               -2147483647);
        parse.add_vertex(x[0], x[1], x[2]);
      }
      vertices = true;
    } else if (keyword == "tetrahedra") {
      const std::int64_t m =
          io_detail::parse_count(path, in.line(), in.require("a tetrahedron count"), "tetrahedron count");
      for (std::int64_t t = 0; t < m; ++t) {
        for (int k = 0; k < 4; ++k) {
          const std::string what = "tetrahedron " + std::to_string(t + 1);
          parse.tets.push_back(
              io_detail::parse_count(path, in.line(), in.require(what), "vertex index", -2147483647) - 1);
          if (k == 0) parse.tet_line.push_back(in.line());
        }
        io_detail::parse_count(path, in.line(),
                               in.require("the reference of tetrahedron " + std::to_string(t + 1)),
                               "reference", -2147483647);
      }
      tetrahedra = true;
    } else if (const int per_entry = skipped_entry_tokens(keyword); per_entry > 0) {
      const std::int64_t count = io_detail::parse_count(path, in.line(), in.require("a count"), "count");
      for (std::int64_t i = 0; i < count * per_entry; ++i) in.require("the entries of " + std::string(token));
      if (count > 0) parse.notes.push_back("read past " + std::to_string(count) + " " + keyword);
    } else {
      io_detail::fail_at_line(path, line,
                              "unknown keyword " + io_detail::quote_token(token) +
                                  " (a MEDIT tet mesh has Vertices, Tetrahedra, Triangles, Edges, ...)");
    }
  }
  if (!vertices) io_detail::fail_at_line(path, in.line(), "no Vertices section");
  if (!tetrahedra) io_detail::fail_at_line(path, in.line(), "no Tetrahedra section");
  return io_detail::finish_tet_mesh(path, std::move(parse), 1);
}

} // namespace iarap
