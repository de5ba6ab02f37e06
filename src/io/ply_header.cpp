#include "ply_format.h"

#include <utility>

namespace iarap::io_detail {

namespace {

bool parse_type(std::string_view name, PlyType& type) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& [n, t] : names)
    if (name == n) {
      type = t;
      return true;
    }
  return false;
}

PlyRole role_of(const std::string& path, const PlyElement& e) {
  PlyRole r;
  const auto find = [&](std::initializer_list<const char*> names) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      for (const char* n : names)
        if (e.properties[i].name == n) return static_cast<int>(i);
    return -1;
  };
  if (e.name == "vertex") {
    r.kind = PlyRole::vertex;
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
    r.kind = e.name == "face" ? PlyRole::face : PlyRole::tristrips;
    r.list = find({"vertex_indices", "vertex_index"});
    if (r.list < 0)
      fail_at_line(path, e.header_line, "element " + e.name + " has no list property vertex_indices");
    const PlyProperty& p = e.properties[static_cast<std::size_t>(r.list)];
    if (!p.is_list || !is_integer(p.type) || !is_integer(p.count_type))
      fail_at_line(path, e.header_line,
                   "property " + p.name + " of element " + e.name + " must be a list of integers");
  }
  return r;
}

PlyEncoding parse_format(const std::string& path, const std::vector<std::string_view>& tokens,
                         std::int64_t line) {
  if (tokens.size() != 3) fail_at_line(path, line, "format line needs an encoding and a version");
  if (tokens[1] == "ascii") return PlyEncoding::ascii;
  if (tokens[1] == "binary_little_endian") return PlyEncoding::little_endian;
  if (tokens[1] == "binary_big_endian") return PlyEncoding::big_endian;
  fail_at_line(path, line, "unknown PLY format " + quote_token(tokens[1]));
}

PlyElement parse_element(const std::string& path, const std::vector<std::string_view>& tokens,
                         std::int64_t line) {
  PlyElement e;
  if (tokens.size() != 3 || !parse_int(tokens[2], e.count) || e.count < 0)
    fail_at_line(path, line, "element line must read 'element <name> <count>'");
  e.name = std::string(tokens[1]);
  e.header_line = line;
  return e;
}

PlyProperty parse_property(const std::string& path, const std::vector<std::string_view>& tokens,
                           std::string_view text, std::int64_t line) {
  PlyProperty p;
  bool ok;
  if (tokens.size() >= 2 && tokens[1] == "list") {
    ok = tokens.size() == 5 && parse_type(tokens[2], p.count_type) && parse_type(tokens[3], p.type);
    if (ok) p.name = std::string(tokens[4]);
    p.is_list = true;
  } else {
    ok = tokens.size() == 3 && parse_type(tokens[1], p.type);
    if (ok) p.name = std::string(tokens[2]);
  }
  if (!ok) fail_at_line(path, line, "bad property line " + quote_token(text));
  return p;
}

} // namespace

std::size_t type_size(PlyType t) {
  switch (t) {
  case PlyType::int8:
  case PlyType::uint8:
    return 1;
  case PlyType::int16:
  case PlyType::uint16:
    return 2;
  case PlyType::int32:
  case PlyType::uint32:
  case PlyType::float32:
    return 4;
  case PlyType::float64:
    return 8;
  }
  return 0;
}

bool is_integer(PlyType t) {
  return t != PlyType::float32 && t != PlyType::float64;
}

PlyHeader read_ply_header(const std::string& path, LineReader& lines) {
  std::vector<std::string_view> tokens;
  std::string_view line;
  if (!lines.next(line) || line != "ply")
    fail_at_line(path, 1, "not a PLY file: the first line must be 'ply'");
  PlyHeader header;
  bool have_format = false, have_end = false;
  while (lines.next(line)) {
    split_tokens(line, tokens);
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") {
      have_end = true;
      break;
    }
    if (tokens[0] == "format") {
      header.encoding = parse_format(path, tokens, lines.line());
      have_format = true;
    } else if (tokens[0] == "element") {
      header.elements.push_back(parse_element(path, tokens, lines.line()));
    } else if (tokens[0] == "property") {
      if (header.elements.empty()) fail_at_line(path, lines.line(), "property before any element");
      header.elements.back().properties.push_back(parse_property(path, tokens, line, lines.line()));
    } else {
      fail_at_line(path, lines.line(), "unknown header keyword " + quote_token(tokens[0]));
    }
  }
  if (!have_end) fail_at_line(path, lines.line(), "file ends inside the header (no end_header)");
  if (!have_format) fail_at_line(path, lines.line(), "header has no format line");
  int vertex_elements = 0;
  for (PlyElement& e : header.elements) {
    e.role = role_of(path, e);
    vertex_elements += e.role.kind == PlyRole::vertex;
  }
  if (vertex_elements != 1)
    fail_at_line(path, lines.line(), "header must declare exactly one element vertex");
  return header;
}

} // namespace iarap::io_detail
