// gmsh's ASCII .msh, versions 2.2 and 4.1 (https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format): the
// nodes and the tetrahedra, every other section and element type read past.
#include "iarap/io/read_tet_mesh.h"

#include "read_tet_mesh_support.h"

#include <string>
#include <unordered_map>

namespace iarap {

namespace {

// Nodes per element of the gmsh types a tet mesh file holds (points, lines, triangles, quads, tets, ...);
// 0 for the others, which are refused when met.
int element_nodes(std::int64_t type) {
  switch (type) {
  case 1:
    return 2; // line
  case 2:
    return 3; // triangle
  case 3:
    return 4; // quadrangle
  case 4:
    return 4; // tetrahedron
  case 5:
    return 8; // hexahedron
  case 6:
    return 6; // prism
  case 7:
    return 5; // pyramid
  case 8:
    return 3; // second-order line
  case 9:
    return 6; // second-order triangle
  case 11:
    return 10; // second-order tetrahedron
  case 15:
    return 1; // point
  default:
    return 0;
  }
}

struct GmshReader {
  const std::string& path;
  io_detail::TokenLines in;
  io_detail::TetParse parse;
  std::unordered_map<std::int64_t, int> node_of_tag;
  std::vector<std::string_view> tokens;
  std::int64_t skipped = 0, quadratic = 0;

  std::int64_t count(size_t k, const char* what, std::int64_t low = 0) {
    if (k >= tokens.size()) io_detail::fail_at_line(path, in.line(), std::string("missing ") + what);
    return io_detail::parse_count(path, in.line(), tokens[k], what, low);
  }

  void add_node(std::int64_t tag, size_t first) {
    if (tokens.size() < first + 3) io_detail::fail_at_line(path, in.line(), "expected x y z");
    if (!node_of_tag.emplace(tag, static_cast<int>(parse.xyz.size() / 3)).second)
      io_detail::fail_at_line(path, in.line(), "node tag " + std::to_string(tag) + " repeats");
    double x[3];
    for (size_t c = 0; c < 3; ++c)
      x[c] = io_detail::parse_coordinate(path, in.line(), tokens[first + c], "coordinate");
    parse.add_vertex(x[0], x[1], x[2]);
  }

  // An element of `type` whose node tags start at tokens[first].
  void add_element(std::int64_t type, size_t first) {
    const int nodes = element_nodes(type);
    if (nodes == 0)
      io_detail::fail_at_line(path, in.line(), "unsupported element type " + std::to_string(type));
    if (tokens.size() < first + static_cast<size_t>(nodes))
      io_detail::fail_at_line(path, in.line(),
                              "element of type " + std::to_string(type) + " needs " + std::to_string(nodes) +
                                  " nodes");
    if (type != 4 && type != 11) {
      ++skipped;
      return;
    }
    if (type == 11) ++quadratic;
    for (size_t k = 0; k < 4; ++k) {
      const std::int64_t tag =
          io_detail::parse_count(path, in.line(), tokens[first + k], "node tag", 0, INT64_MAX);
      const auto it = node_of_tag.find(tag);
      if (it == node_of_tag.end())
        io_detail::fail_at_line(path, in.line(), "node tag " + std::to_string(tag) + " is not in $Nodes");
      parse.tets.push_back(it->second);
    }
    parse.tet_line.push_back(in.line());
  }

  void nodes_v2() {
    in.require(tokens, "the node count");
    const std::int64_t n = count(0, "node count");
    for (std::int64_t v = 0; v < n; ++v) {
      in.require(tokens, "node " + std::to_string(v + 1) + " of " + std::to_string(n));
      add_node(count(0, "node tag", 0), 1);
    }
  }

  void elements_v2() {
    in.require(tokens, "the element count");
    const std::int64_t m = count(0, "element count");
    for (std::int64_t e = 0; e < m; ++e) {
      in.require(tokens, "element " + std::to_string(e + 1) + " of " + std::to_string(m));
      add_element(count(1, "element type"), 3 + static_cast<size_t>(count(2, "tag count")));
    }
  }

  void nodes_v4() {
    in.require(tokens, "'numEntityBlocks numNodes minNodeTag maxNodeTag'");
    const std::int64_t blocks = count(0, "entity block count");
    for (std::int64_t b = 0; b < blocks; ++b) {
      in.require(tokens, "'entityDim entityTag parametric numNodesInBlock'");
      const std::int64_t n = count(3, "nodes in block");
      std::vector<std::int64_t> tags;
      for (std::int64_t v = 0; v < n; ++v) {
        in.require(tokens, "a node tag");
        tags.push_back(count(0, "node tag"));
      }
      for (std::int64_t v = 0; v < n; ++v) {
        in.require(tokens, "the coordinates of node " + std::to_string(tags[static_cast<size_t>(v)]));
        add_node(tags[static_cast<size_t>(v)], 0); // parametric nodes' u v w follow x y z: read past
      }
    }
  }

  void elements_v4() {
    in.require(tokens, "'numEntityBlocks numElements minElementTag maxElementTag'");
    const std::int64_t blocks = count(0, "entity block count");
    for (std::int64_t b = 0; b < blocks; ++b) {
      in.require(tokens, "'entityDim entityTag elementType numElementsInBlock'");
      const std::int64_t type = count(2, "element type");
      const std::int64_t m = count(3, "elements in block");
      for (std::int64_t e = 0; e < m; ++e) {
        in.require(tokens, "element " + std::to_string(e + 1) + " of its block");
        add_element(type, 1);
      }
    }
  }

  // Reads up to the line `$End<section>`.
  void expect_end(const std::string& section) {
    in.require(tokens, "$End" + section);
    if (tokens[0] != "$End" + section)
      io_detail::fail_at_line(path, in.line(),
                              "expected $End" + section + ", got " + io_detail::quote_token(tokens[0]));
  }
};

} // namespace

TetMesh read_gmsh(const std::string& path) {
  const std::string text = io_detail::read_whole_file(path);
  GmshReader r{path, io_detail::TokenLines(path, text, false), {}, {}, {}};
  int version = 0; // 2 or 4
  bool nodes = false, elements = false;
  while (r.in.next(r.tokens)) {
    const std::string section(r.tokens[0]);
    if (section == "$MeshFormat") {
      r.in.require(r.tokens, "'version file-type data-size'");
      const std::string v(r.tokens[0]);
      if (v.rfind("2.", 0) == 0)
        version = 2;
      else if (v == "4.1")
        version = 4;
      else
        io_detail::fail_at_line(path, r.in.line(),
                                "gmsh format " + io_detail::quote_token(r.tokens[0]) +
                                    " (readable: 2.2, 4.1)");
      if (r.count(1, "file type") != 0)
        io_detail::fail_at_line(path, r.in.line(),
                                "binary .msh; save it as ASCII (gmsh -save -format msh22)");
      r.expect_end("MeshFormat");
    } else if (section == "$Nodes" || section == "$Elements") {
      if (version == 0) io_detail::fail_at_line(path, r.in.line(), section + " before $MeshFormat");
      if (section == "$Nodes") {
        version == 2 ? r.nodes_v2() : r.nodes_v4();
        nodes = true;
      } else {
        if (!nodes) io_detail::fail_at_line(path, r.in.line(), "$Elements before $Nodes");
        version == 2 ? r.elements_v2() : r.elements_v4();
        elements = true;
      }
      r.expect_end(section.substr(1));
    } else if (section.size() > 1 && section[0] == '$') { // another section: read past it
      const std::string end = "$End" + section.substr(1);
      while (r.in.next(r.tokens) && r.tokens[0] != end) {
      }
    } else {
      io_detail::fail_at_line(path, r.in.line(),
                              "expected a $Section, got " + io_detail::quote_token(r.tokens[0]));
    }
  }
  if (!nodes) io_detail::fail_at_line(path, r.in.line(), "no $Nodes section");
  if (!elements) io_detail::fail_at_line(path, r.in.line(), "no $Elements section");
  if (r.skipped > 0)
    r.parse.notes.push_back("read past " + std::to_string(r.skipped) + " elements that are not tetrahedra");
  if (r.quadratic > 0)
    r.parse.notes.push_back("kept the 4 corners of " + std::to_string(r.quadratic) + " quadratic tetrahedra");
  return io_detail::finish_tet_mesh(path, std::move(r.parse), 0);
}

} // namespace iarap
