#include "line_tokens.h"

#include "iarap/core/errors.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace iarap::detail {

std::string where(const std::string& source, int line) {
  return source + ":" + std::to_string(line) + ": ";
}

// Splits a line (comment already removed) into blank-separated tokens.
std::vector<std::string> tokens_of(const std::string& text) {
  std::vector<std::string> tokens;
  std::istringstream in(text);
  std::string token;
  while (in >> token) tokens.push_back(token);
  return tokens;
}

long long parse_index(const std::string& token, const std::string& at) {
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (end == token.c_str() || *end != '\0' || errno == ERANGE) {
    throw InputError(at + "bad vertex index '" + token + "' (expected a non-negative integer)");
  }
  return value;
}

double parse_coordinate(const std::string& token, const std::string& at, const char* name) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') {
    throw InputError(at + "bad " + name + " coordinate '" + token + "' (expected a number)");
  }
  if (!std::isfinite(value)) {
    throw InputError(at + "non-finite " + name + " coordinate '" + token + "'");
  }
  return value;
}

int for_each_vertex_line(
    std::istream& in, const std::string& source, int num_vertices, size_t count, const char* format,
    const std::function<void(int, const std::vector<std::string>&, const std::string&, int)>& line) {
  std::string text;
  int number = 0, lines = 0;
  while (std::getline(in, text)) {
    ++number;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    const auto tokens = tokens_of(text);
    if (tokens.empty()) continue;
    const std::string at = where(source, number);
    if (tokens.size() != count)
      throw InputError(at + "expected '" + format + "', found " + std::to_string(tokens.size()) +
                       " token(s)");
    const long long index = parse_index(tokens[0], at);
    if (index < 0 || index >= num_vertices)
      throw InputError(at + "vertex index " + tokens[0] + " out of range; the mesh has " +
                       std::to_string(num_vertices) + " vertices (valid: 0.." +
                       std::to_string(num_vertices - 1) + ")");
    line(static_cast<int>(index), tokens, at, number);
    ++lines;
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(number));
  return lines;
}

} // namespace iarap::detail
