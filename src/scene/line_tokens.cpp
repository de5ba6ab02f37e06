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

} // namespace iarap::detail
