// Hand-written: Debian has no C/C++ PLY library (rply, happly, tinyply are not packaged) and the format
// needs exact errors, all three encodings, arbitrary list types and the `tristrips` element.
#include "face_builder.h"
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "text_reader.h"

#include <algorithm>
#include <cstring>

namespace iarap {

using io_detail::fail_at_line;
using io_detail::fail_at_offset;
using io_detail::quote_token;

namespace {

enum class Encoding { ascii, little_endian, big_endian };
enum class Type { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

struct Property {
  std::string name;
  Type type = Type::float32; // the value type (of the items, for a list)
  bool is_list = false;
  Type count_type = Type::uint8; // lists only
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::int64_t header_line = 0;
  std::vector<Property> properties;
};

bool parse_type(std::string_view name, Type& type) {
  static const std::pair<const char*, Type> names[] = {
      {"char", Type::int8},      {"int8", Type::int8},       {"uchar", Type::uint8},
      {"uint8", Type::uint8},    {"short", Type::int16},     {"int16", Type::int16},
      {"ushort", Type::uint16},  {"uint16", Type::uint16},   {"int", Type::int32},
      {"int32", Type::int32},    {"uint", Type::uint32},     {"uint32", Type::uint32},
      {"float", Type::float32},  {"float32", Type::float32}, {"double", Type::float64},
      {"float64", Type::float64}};
  for (const auto& [n, t] : names)
    if (name == n) {
      type = t;
      return true;
    }
  return false;
}

std::size_t type_size(Type t) {
  switch (t) {
  case Type::int8:
  case Type::uint8:
    return 1;
  case Type::int16:
  case Type::uint16:
    return 2;
  case Type::int32:
  case Type::uint32:
  case Type::float32:
    return 4;
  case Type::float64:
    return 8;
  }
  return 0;
}

bool is_integer(Type t) {
  return t != Type::float32 && t != Type::float64;
}

// Reads one binary scalar at p (bounds already checked) as a double; integers convert exactly.
double read_binary(const unsigned char* p, Type t, bool swap) {
  unsigned char b[8];
  const std::size_t n = type_size(t);
  for (std::size_t i = 0; i < n; ++i) b[i] = swap ? p[n - 1 - i] : p[i];
  switch (t) {
  case Type::int8: {
    std::int8_t v;
    std::memcpy(&v, b, 1);
    return v;
  }
  case Type::uint8:
    return b[0];
  case Type::int16: {
    std::int16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  case Type::uint16: {
    std::uint16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  case Type::int32: {
    std::int32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case Type::uint32: {
    std::uint32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case Type::float32: {
    float v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case Type::float64: {
    double v;
    std::memcpy(&v, b, 8);
    return v;
  }
  }
  return 0.0;
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// What the reader does with an element, and which of its properties it needs.
struct Role {
  enum Kind { vertex, face, tristrips, skip } kind = skip;
  int x = -1, y = -1, z = -1; // property positions of the coordinates (vertex)
  int list = -1;              // property position of the index list (face, tristrips)
};

Role role_of(const std::string& path, const Element& e) {
  Role r;
  const auto find = [&](std::initializer_list<const char*> names) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      for (const char* n : names)
        if (e.properties[i].name == n) return static_cast<int>(i);
    return -1;
  };
  if (e.name == "vertex") {
    r.kind = Role::vertex;
    r.x = find({"x"});
    r.y = find({"y"});
    r.z = find({"z"});
    if (r.x < 0 || r.y < 0 || r.z < 0)
      fail_at_line(path, e.header_line, "element vertex lacks one of the properties x, y, z");
    for (int i : {r.x, r.y, r.z})
      if (e.properties[static_cast<std::size_t>(i)].is_list)
        fail_at_line(path, e.header_line,
                     "vertex property " + e.properties[static_cast<std::size_t>(i)].name + " is a list");
  } else if (e.name == "face" || e.name == "tristrips") {
    r.kind = e.name == "face" ? Role::face : Role::tristrips;
    r.list = find({"vertex_indices", "vertex_index"});
    if (r.list < 0)
      fail_at_line(path, e.header_line, "element " + e.name + " has no list property vertex_indices");
    const Property& p = e.properties[static_cast<std::size_t>(r.list)];
    if (!p.is_list || !is_integer(p.type) || !is_integer(p.count_type))
      fail_at_line(path, e.header_line,
                   "property " + p.name + " of element " + e.name + " must be a list of integers");
  }
  return r;
}

} // namespace

MeshData read_ply(const std::string& path) {
  const std::string text = io_detail::read_whole_file(path);
  io_detail::LineReader lines(text, io_detail::utf8_bom_length(text));
  std::vector<std::string_view> tokens;
  std::string_view line;

  // ---- header
  if (!lines.next(line) || line != "ply")
    fail_at_line(path, 1, "not a PLY file: the first line must be 'ply'");
  Encoding encoding = Encoding::ascii;
  bool have_format = false, have_end = false;
  std::vector<Element> elements;
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") {
      have_end = true;
      break;
    }
    if (tokens[0] == "format") {
      if (tokens.size() != 3) fail_at_line(path, lines.line(), "format line needs an encoding and a version");
      if (tokens[1] == "ascii")
        encoding = Encoding::ascii;
      else if (tokens[1] == "binary_little_endian")
        encoding = Encoding::little_endian;
      else if (tokens[1] == "binary_big_endian")
        encoding = Encoding::big_endian;
      else
        fail_at_line(path, lines.line(), "unknown PLY format " + quote_token(tokens[1]));
      have_format = true;
    } else if (tokens[0] == "element") {
      Element e;
      if (tokens.size() != 3 || !io_detail::parse_int(tokens[2], e.count) || e.count < 0)
        fail_at_line(path, lines.line(), "element line must read 'element <name> <count>'");
      e.name = std::string(tokens[1]);
      e.header_line = lines.line();
      elements.push_back(std::move(e));
    } else if (tokens[0] == "property") {
      if (elements.empty()) fail_at_line(path, lines.line(), "property before any element");
      Property p;
      bool ok;
      if (tokens.size() >= 2 && tokens[1] == "list") {
        ok = tokens.size() == 5 && parse_type(tokens[2], p.count_type) && parse_type(tokens[3], p.type);
        if (ok) p.name = std::string(tokens[4]);
        p.is_list = true;
      } else {
        ok = tokens.size() == 3 && parse_type(tokens[1], p.type);
        if (ok) p.name = std::string(tokens[2]);
      }
      if (!ok) fail_at_line(path, lines.line(), "bad property line " + quote_token(line));
      elements.back().properties.push_back(std::move(p));
    } else {
      fail_at_line(path, lines.line(), "unknown header keyword " + quote_token(tokens[0]));
    }
  }
  if (!have_end) fail_at_line(path, lines.line(), "file ends inside the header (no end_header)");
  if (!have_format) fail_at_line(path, lines.line(), "header has no format line");

  std::vector<Role> roles;
  int vertex_elements = 0;
  for (const Element& e : elements) {
    roles.push_back(role_of(path, e));
    if (roles.back().kind == Role::vertex) ++vertex_elements;
  }
  if (vertex_elements != 1)
    fail_at_line(path, lines.line(), "header must declare exactly one element vertex");

  const io_detail::Location where_kind =
      encoding == Encoding::ascii ? io_detail::Location::line : io_detail::Location::byte_offset;
  io_detail::FaceBuilder faces(path, where_kind);
  std::vector<double> positions;
  std::int64_t num_vertices = 0;
  std::vector<std::int64_t> list;

  if (encoding == Encoding::ascii) {
    for (std::size_t ei = 0; ei < elements.size(); ++ei) {
      const Element& e = elements[ei];
      const Role& r = roles[ei];
      const std::int64_t cap =
          static_cast<std::int64_t>(lines.remaining_bytes() / 2); // >= 2 bytes per record
      if (r.kind == Role::vertex) positions.reserve(static_cast<std::size_t>(3 * std::min(e.count, cap)));
      if (r.kind == Role::face) faces.reserve_triangles(static_cast<std::size_t>(std::min(e.count, cap)));
      double xyz[3] = {0, 0, 0};
      for (std::int64_t i = 0; i < e.count; ++i) {
        do {
          if (!lines.next(line))
            fail_at_line(path, lines.line(),
                         "file ends after " + std::to_string(i) + " of " + std::to_string(e.count) + " " +
                             e.name + " records");
          io_detail::split_tokens(line, tokens);
        } while (tokens.empty());
        std::size_t t = 0;
        const auto take = [&](const Property& p) -> std::string_view {
          if (t >= tokens.size())
            fail_at_line(path, lines.line(),
                         e.name + " " + std::to_string(i) + ": line ends before property " + p.name);
          return tokens[t++];
        };
        for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
          const Property& p = e.properties[pi];
          const int pos = static_cast<int>(pi);
          if (!p.is_list) {
            const std::string_view tok = take(p);
            double value;
            if (!io_detail::parse_double(tok, value))
              fail_at_line(path, lines.line(),
                           e.name + " " + std::to_string(i) + ": bad value " + quote_token(tok) +
                               " for property " + p.name);
            if (pos == r.x) xyz[0] = value;
            if (pos == r.y) xyz[1] = value;
            if (pos == r.z) xyz[2] = value;
            continue;
          }
          const std::string_view count_tok = take(p);
          std::int64_t n;
          if (!io_detail::parse_int(count_tok, n) || n < 0)
            fail_at_line(path, lines.line(),
                         e.name + " " + std::to_string(i) + ": bad list length " + quote_token(count_tok));
          if (static_cast<std::int64_t>(tokens.size() - t) < n)
            fail_at_line(path, lines.line(),
                         e.name + " " + std::to_string(i) + ": list " + p.name + " declares " +
                             std::to_string(n) + " items but the line has " +
                             std::to_string(tokens.size() - t));
          const bool wanted = pos == r.list;
          if (wanted) list.resize(static_cast<std::size_t>(n));
          for (std::int64_t k = 0; k < n; ++k) {
            const std::string_view tok = tokens[t++];
            if (!wanted) continue;
            if (!io_detail::parse_int(tok, list[static_cast<std::size_t>(k)]))
              fail_at_line(path, lines.line(),
                           e.name + " " + std::to_string(i) + ": bad vertex index " + quote_token(tok));
          }
        }
        if (t != tokens.size())
          fail_at_line(path, lines.line(),
                       e.name + " " + std::to_string(i) + ": " + std::to_string(tokens.size() - t) +
                           " values more than the header declares");
        if (r.kind == Role::vertex) positions.insert(positions.end(), xyz, xyz + 3);
        if (r.kind == Role::face) faces.add_polygon(list, lines.line());
        if (r.kind == Role::tristrips) faces.add_strip(list, lines.line());
      }
      if (r.kind == Role::vertex) num_vertices = e.count;
    }
    while (lines.next(line)) {
      io_detail::split_tokens(line, tokens);
      if (!tokens.empty())
        fail_at_line(path, lines.line(), "unexpected data after the last element the header declares");
    }
  } else {
    const bool swap = (encoding == Encoding::little_endian) != host_is_little_endian();
    const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
    const std::size_t size = text.size();
    std::size_t pos = lines.offset();
    for (std::size_t ei = 0; ei < elements.size(); ++ei) {
      const Element& e = elements[ei];
      const Role& r = roles[ei];
      std::size_t fixed = 0; // record size when the element has no lists
      bool has_list = false;
      for (const Property& p : e.properties) {
        has_list = has_list || p.is_list;
        fixed += type_size(p.is_list ? p.count_type : p.type);
      }
      const std::size_t remaining = size - pos;
      // A count the remaining bytes cannot hold is rejected before anything is allocated for it.
      const std::size_t min_record = std::max<std::size_t>(fixed, 1);
      if (static_cast<std::uint64_t>(e.count) > remaining / min_record)
        fail_at_offset(path, static_cast<std::int64_t>(pos),
                       "header declares " + std::to_string(e.count) + " " + e.name + " records of at least " +
                           std::to_string(min_record) + " bytes but only " + std::to_string(remaining) +
                           " bytes follow");
      if (r.kind == Role::vertex) positions.reserve(static_cast<std::size_t>(3 * e.count));
      if (r.kind == Role::face) faces.reserve_triangles(static_cast<std::size_t>(e.count));
      const auto need = [&](std::size_t n, std::int64_t i) {
        if (n > size - pos)
          fail_at_offset(path, static_cast<std::int64_t>(pos),
                         "file ends inside " + e.name + " record " + std::to_string(i) + " of " +
                             std::to_string(e.count));
      };
      double xyz[3] = {0, 0, 0};
      for (std::int64_t i = 0; i < e.count; ++i) {
        const std::size_t record_start = pos;
        if (!has_list) need(fixed, i);
        for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
          const Property& p = e.properties[pi];
          const int ppos = static_cast<int>(pi);
          if (!p.is_list) {
            const std::size_t n = type_size(p.type);
            need(n, i);
            if (ppos == r.x || ppos == r.y || ppos == r.z) {
              const double value = read_binary(bytes + pos, p.type, swap);
              xyz[ppos == r.x ? 0 : (ppos == r.y ? 1 : 2)] = value;
            }
            pos += n;
            continue;
          }
          const std::size_t cn = type_size(p.count_type);
          need(cn, i);
          const double count_value = read_binary(bytes + pos, p.count_type, swap);
          if (count_value < 0)
            fail_at_offset(path, static_cast<std::int64_t>(pos),
                           e.name + " " + std::to_string(i) + ": negative list length " +
                               std::to_string(static_cast<std::int64_t>(count_value)));
          pos += cn;
          const std::size_t n = static_cast<std::size_t>(count_value);
          const std::size_t item = type_size(p.type);
          if (n > (size - pos) / item) need(n * item, i);
          if (ppos == r.list) {
            list.resize(n);
            for (std::size_t k = 0; k < n; ++k)
              list[k] = static_cast<std::int64_t>(read_binary(bytes + pos + k * item, p.type, swap));
          }
          pos += n * item;
        }
        if (r.kind == Role::vertex) positions.insert(positions.end(), xyz, xyz + 3);
        if (r.kind == Role::face) faces.add_polygon(list, static_cast<std::int64_t>(record_start));
        if (r.kind == Role::tristrips) faces.add_strip(list, static_cast<std::int64_t>(record_start));
      }
      if (r.kind == Role::vertex) num_vertices = e.count;
    }
    if (pos != size)
      fail_at_offset(path, static_cast<std::int64_t>(pos),
                     std::to_string(size - pos) + " bytes after the last element the header declares");
  }

  MeshData mesh;
  mesh.F = faces.finish(num_vertices, mesh.notes);
  mesh.V = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(positions.data(),
                                                                                       num_vertices, 3);
  return mesh;
}

} // namespace iarap
