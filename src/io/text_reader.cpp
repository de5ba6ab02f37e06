#include "text_reader.h"

#include "iarap/core/errors.h"

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace iarap::io_detail {

std::string read_whole_file(const std::string& path) {
  // A folder opens as a stream on Linux and reports a size of 2^63: say what it is before reading.
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError(path +
                     ": is a folder, not a mesh file; give the path of a .obj, .off, .ply or .stl file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0 || !std::filesystem::is_regular_file(path, error))
    throw InputError(path + ": not a regular file (cannot determine its size); give the path of a mesh file");
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(bytes.data(), size))
    throw InputError(path + ": read failed: " + std::strerror(errno));
  return bytes;
}

void fail_at_line(const std::string& path, std::int64_t line, const std::string& message) {
  throw InputError(path + ":" + std::to_string(line) + ": " + message);
}

void fail_at_offset(const std::string& path, std::int64_t offset, const std::string& message) {
  throw InputError(path + ": byte offset " + std::to_string(offset) + ": " + message);
}

bool parse_double(std::string_view token, double& value) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first; // from_chars rejects a leading '+', files use it
  const auto [end, ec] = std::from_chars(first, last, value);
  // Magnitudes beyond double (1e999, 1e-999) are errors for from_chars but mean Inf or 0 in a mesh file;
  // strtod rounds them that way.
  if (ec == std::errc::result_out_of_range && end == last) {
    value = std::strtod(std::string(first, last).c_str(), nullptr);
    return true;
  }
  return ec == std::errc() && end == last && first != last;
}

bool parse_int(std::string_view token, std::int64_t& value) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto [end, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && end == last && first != last;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    while (i < n && (line[i] == ' ' || line[i] == '\t' || line[i] == '\v' || line[i] == '\f')) ++i;
    const std::size_t start = i;
    while (i < n && !(line[i] == ' ' || line[i] == '\t' || line[i] == '\v' || line[i] == '\f')) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

LineReader::LineReader(std::string_view text, std::size_t start, std::int64_t lines_before)
    : text_(text), pos_(start), line_(lines_before) {}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  std::size_t stop = end;
  if (stop > pos_ && text_[stop - 1] == '\r') --stop;
  line = text_.substr(pos_, stop - pos_);
  pos_ = end < text_.size() ? end + 1 : end;
  ++line_;
  return true;
}

std::size_t utf8_bom_length(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
}

std::string quote_token(std::string_view token) {
  std::string out = "'";
  for (char c : token.substr(0, 40))
    out += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
  if (token.size() > 40) out += "...";
  return out + "'";
}

} // namespace iarap::io_detail
