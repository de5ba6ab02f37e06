// Internal: the pieces of read_ply. The header becomes a list of elements, each with the role the reader
// gives it (vertex, face, tristrips or skipped); the ASCII and the binary bodies are read by one function
// each, record by record, into vertex positions and a FaceBuilder (faces fan-triangulated, triangle strips
// unrolled).
#pragma once
#include "face_builder.h"
#include "text_reader.h"

#include <cstdint>
#include <string>
#include <vector>

namespace iarap::io_detail {

enum class PlyEncoding { ascii, little_endian, big_endian };
enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::float32; // the value type (of the items, for a list)
  bool is_list = false;
  PlyType count_type = PlyType::uint8; // lists only
};

// What the reader does with an element, and which of its properties it needs.
struct PlyRole {
  enum Kind { vertex, face, tristrips, skip } kind = skip;
  int x = -1, y = -1, z = -1; // property positions of the coordinates (vertex)
  int list = -1;              // property position of the index list (face, tristrips)
};

struct PlyElement {
  std::string name;
  std::int64_t count = 0;
  std::int64_t header_line = 0;
  std::vector<PlyProperty> properties;
  PlyRole role;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::ascii;
  std::vector<PlyElement> elements; // exactly one of role vertex
};

// What the body gives the mesh: 3 coordinates per vertex, and the faces.
struct PlyBody {
  PlyBody(const std::string& path, Location kind) : faces(path, kind) {}
  std::vector<double> positions;
  std::int64_t num_vertices = 0;
  FaceBuilder faces;
};

// Reads the header from the first line of `lines` through end_header. Throws InputError naming the line.
PlyHeader read_ply_header(const std::string& path, LineReader& lines);

// Read the records of every element after the header: from `lines` (ASCII), or from byte lines.offset() of
// `text` on (binary). Throw InputError naming the line or byte offset.
void read_ply_ascii_body(const std::string& path, const PlyHeader& header, LineReader& lines, PlyBody& body);
void read_ply_binary_body(const std::string& path, const PlyHeader& header, const std::string& text,
                          std::size_t offset, PlyBody& body);

// Hands one record to the mesh by its element's role: a vertex's coordinates, a face's polygon, a
// tristrips record's strip (unrolled by FaceBuilder::add_strip). `where` is the line or byte offset.
inline void store_ply_record(const PlyRole& role, const double (&xyz)[3],
                             const std::vector<std::int64_t>& list, std::int64_t where, PlyBody& body) {
  if (role.kind == PlyRole::vertex) body.positions.insert(body.positions.end(), xyz, xyz + 3);
  if (role.kind == PlyRole::face) body.faces.add_polygon(list, where);
  if (role.kind == PlyRole::tristrips) body.faces.add_strip(list, where);
}

bool is_integer(PlyType type);
std::size_t type_size(PlyType type);

} // namespace iarap::io_detail
