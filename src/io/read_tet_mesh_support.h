// Internal: what the tet readers (MEDIT, TetGen, gmsh) share: token and line cursors over a text with line
// numbers, the collected arrays, and the checks and orientation rule (tet_mesh.h) that end every reader.
#pragma once
#include "iarap/io/tet_mesh.h"

#include "text_reader.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace iarap::io_detail {

// The tokens of a text one line at a time, blank lines and `#` comments (when asked) skipped.
class TokenLines {
public:
  TokenLines(const std::string& path, std::string_view text, bool hash_comments);
  // The tokens of the next non-blank line; false at the end of the text.
  bool next(std::vector<std::string_view>& tokens);
  // The same, or "path:line: unexpected end of file, expected <what>".
  void require(std::vector<std::string_view>& tokens, const std::string& what);
  std::int64_t line() const { return lines_.line(); }
  const std::string& path() const { return path_; }

private:
  std::string path_;
  LineReader lines_; // over the caller's text, which outlives the cursor
  bool hash_comments_;
};

// The tokens of a text one by one across lines (MEDIT's free form).
class TokenStream {
public:
  TokenStream(const std::string& path, std::string_view text, bool hash_comments);
  bool next(std::string_view& token);
  // The next token, or "path:line: unexpected end of file, expected <what>".
  std::string_view require(const std::string& what);
  std::int64_t line() const { return lines_.line(); }
  const std::string& path() const { return lines_.path(); }

private:
  TokenLines lines_;
  std::vector<std::string_view> tokens_;
  size_t at_ = 0;
};

// Parses `token` as a number / an integer in [low, high], or fails at `line` naming `what` and the token.
double parse_coordinate(const std::string& path, std::int64_t line, std::string_view token, const char* what);
std::int64_t parse_count(const std::string& path, std::int64_t line, std::string_view token, const char* what,
                         std::int64_t low = 0, std::int64_t high = 2147483647);

// What a reader collects: positions (3 per vertex), tetrahedra (4 0-based indices each, not yet checked) with
// the line each came from, and notes.
struct TetParse {
  std::vector<double> xyz;
  std::vector<std::int64_t> tets;
  std::vector<std::int64_t> tet_line;
  std::vector<std::string> notes;
  void add_vertex(double x, double y, double z) { xyz.insert(xyz.end(), {x, y, z}); }
};

// The mesh from parse: indices in range (the message gives the file's index, base = its first index),
// find_tet_problem, then the orientation rule; errors name path:line of the tetrahedron.
TetMesh finish_tet_mesh(const std::string& path, TetParse parse, int base);

} // namespace iarap::io_detail
