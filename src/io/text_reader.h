// Internal helpers shared by the mesh readers: whole-file loading, line splitting with line numbers,
// exact token parsing and error messages in the "path:line: message" / "path: byte offset N: message" form.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace iarap::io_detail {

// The whole file as bytes. Throws InputError "path: cannot open: reason".
std::string read_whole_file(const std::string& path);

[[noreturn]] void fail_at_line(const std::string& path, std::int64_t line, const std::string& message);
[[noreturn]] void fail_at_offset(const std::string& path, std::int64_t offset, const std::string& message);

// Parse the whole token or return false. Doubles accept nan and inf (validation reports them later).
bool parse_double(std::string_view token, double& value);
bool parse_int(std::string_view token, std::int64_t& value);

// Splits a line at spaces and tabs into `tokens` (cleared first).
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

// Yields the lines of a text one by one (without '\n' or '\r'), counting them from 1.
class LineReader {
public:
  explicit LineReader(std::string_view text, std::size_t start = 0, std::int64_t lines_before = 0);
  bool next(std::string_view& line);
  std::int64_t line() const { return line_; } // number of the line last returned
  std::size_t offset() const { return pos_; } // byte offset just past the line last returned
  std::size_t remaining_bytes() const { return text_.size() - pos_; }

private:
  std::string_view text_;
  std::size_t pos_;
  std::int64_t line_;
};

// 3 when the text starts with a UTF-8 byte-order mark (some Windows editors write one), else 0: text
// readers start after it, so that it is not glued to the first keyword.
std::size_t utf8_bom_length(std::string_view text);

// Returns "name" quoted and shortened to at most 40 characters, for error messages about bad tokens.
std::string quote_token(std::string_view token);

} // namespace iarap::io_detail
