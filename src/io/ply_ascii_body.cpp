#include "ply_format.h"

#include <algorithm>

namespace iarap::io_detail {

namespace {

// Parses record i of element e from the tokens of its line: the coordinates into xyz (vertex), the index
// list of the role's list property into list; other properties are checked and skipped.
void parse_ascii_record(const std::string& path, const PlyElement& e, std::int64_t i,
                        const std::vector<std::string_view>& tokens, std::int64_t line, double (&xyz)[3],
                        std::vector<std::int64_t>& list) {
  const PlyRole& r = e.role;
  std::size_t t = 0;
  const auto take = [&](const PlyProperty& p) -> std::string_view {
    if (t >= tokens.size())
      fail_at_line(path, line, e.name + " " + std::to_string(i) + ": line ends before property " + p.name);
    return tokens[t++];
  };
  for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
    const PlyProperty& p = e.properties[pi];
    const int pos = static_cast<int>(pi);
    if (!p.is_list) {
      const std::string_view tok = take(p);
      double value;
      if (!parse_double(tok, value))
        fail_at_line(path, line,
                     e.name + " " + std::to_string(i) + ": bad value " + quote_token(tok) + " for property " +
                         p.name);
      if (pos == r.x) xyz[0] = value;
      if (pos == r.y) xyz[1] = value;
      if (pos == r.z) xyz[2] = value;
      continue;
    }
    const std::string_view count_tok = take(p);
    std::int64_t n;
    if (!parse_int(count_tok, n) || n < 0)
      fail_at_line(path, line,
                   e.name + " " + std::to_string(i) + ": bad list length " + quote_token(count_tok));
    if (static_cast<std::int64_t>(tokens.size() - t) < n)
      fail_at_line(path, line,
                   e.name + " " + std::to_string(i) + ": list " + p.name + " declares " + std::to_string(n) +
                       " items but the line has " + std::to_string(tokens.size() - t));
    const bool wanted = pos == r.list;
    if (wanted) list.resize(static_cast<std::size_t>(n));
    for (std::int64_t k = 0; k < n; ++k) {
      const std::string_view tok = tokens[t++];
      if (!wanted) continue;
      if (!parse_int(tok, list[static_cast<std::size_t>(k)]))
        fail_at_line(path, line, e.name + " " + std::to_string(i) + ": bad vertex index " + quote_token(tok));
    }
  }
  if (t != tokens.size())
    fail_at_line(path, line,
                 e.name + " " + std::to_string(i) + ": " + std::to_string(tokens.size() - t) +
                     " values more than the header declares");
}

} // namespace

void read_ply_ascii_body(const std::string& path, const PlyHeader& header, LineReader& lines, PlyBody& body) {
  std::vector<std::string_view> tokens;
  std::string_view line;
  std::vector<std::int64_t> list;
  for (const PlyElement& e : header.elements) {
    const PlyRole& r = e.role;
    const std::int64_t cap = static_cast<std::int64_t>(lines.remaining_bytes() / 2); // >= 2 bytes per record
    if (r.kind == PlyRole::vertex)
      body.positions.reserve(static_cast<std::size_t>(3 * std::min(e.count, cap)));
    if (r.kind == PlyRole::face)
      body.faces.reserve_triangles(static_cast<std::size_t>(std::min(e.count, cap)));
    double xyz[3] = {0, 0, 0};
    for (std::int64_t i = 0; i < e.count; ++i) {
      do {
        if (!lines.next(line))
          fail_at_line(path, lines.line(),
                       "file ends after " + std::to_string(i) + " of " + std::to_string(e.count) + " " +
                           e.name + " records");
        split_tokens(line, tokens);
      } while (tokens.empty());
      parse_ascii_record(path, e, i, tokens, lines.line(), xyz, list);
      store_ply_record(r, xyz, list, lines.line(), body);
    }
    if (r.kind == PlyRole::vertex) body.num_vertices = e.count;
  }
  while (lines.next(line)) {
    split_tokens(line, tokens);
    if (!tokens.empty())
      fail_at_line(path, lines.line(), "unexpected data after the last element the header declares");
  }
}

} // namespace iarap::io_detail
