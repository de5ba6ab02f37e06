// Constraints files are a trivial line format, so they are parsed by hand with strtol/strtod
// (exact token checks and file:line messages, which stream extraction does not give).
#include "iarap/scene/read_constraints.h"

#include "iarap/core/errors.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace iarap {
namespace {

struct Parsed {
  int line;
  Eigen::Vector3d target;
};

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

} // namespace

ConstraintSet parse_constraints(std::istream& in, const std::string& source, int num_vertices) {
  std::vector<int> order; // vertex indices in order of first appearance
  std::unordered_map<int, Parsed> seen;
  ConstraintSet result;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    const auto tokens = tokens_of(text);
    if (tokens.empty()) continue;
    const std::string at = where(source, line);
    // 'index x y' is a target in the plane z = 0 (a planar mesh).
    if (tokens.size() != 4 && tokens.size() != 3) {
      throw InputError(at + "expected 'index x y z' (or 'index x y' in the plane z = 0), found " +
                       std::to_string(tokens.size()) + " token(s)");
    }
    const long long index = parse_index(tokens[0], at);
    if (index < 0 || index >= num_vertices) {
      throw InputError(at + "vertex index " + tokens[0] + " out of range; the mesh has " +
                       std::to_string(num_vertices) + " vertices (valid: 0.." +
                       std::to_string(num_vertices - 1) + ")");
    }
    const Eigen::Vector3d target(parse_coordinate(tokens[1], at, "x"), parse_coordinate(tokens[2], at, "y"),
                                 tokens.size() == 4 ? parse_coordinate(tokens[3], at, "z") : 0.0);
    const int vertex = static_cast<int>(index);
    const auto found = seen.find(vertex);
    if (found == seen.end()) {
      seen.emplace(vertex, Parsed{line, target});
      order.push_back(vertex);
    } else if (found->second.target == target) {
      result.warnings.push_back(at + "vertex " + std::to_string(vertex) + " repeats line " +
                                std::to_string(found->second.line) + " with the same target; merged");
    } else {
      throw InputError(at + "vertex " + std::to_string(vertex) + " already constrained at line " +
                       std::to_string(found->second.line) + " to a different target");
    }
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(line));
  if (order.empty()) throw InputError(source + ": no constraints (expected lines 'index x y z')");
  result.fixed.resize(static_cast<Eigen::Index>(order.size()));
  result.targets.resize(static_cast<Eigen::Index>(order.size()), 3);
  for (std::size_t k = 0; k < order.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    result.fixed(row) = order[k];
    result.targets.row(row) = seen.at(order[k]).target.transpose();
    result.origins.push_back(source + ":" + std::to_string(seen.at(order[k]).line));
  }
  return result;
}

ConstraintSet read_constraints(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open constraints file");
  return parse_constraints(in, path, num_vertices);
}

} // namespace iarap
