// Constraints files are a trivial line format, so they are parsed by hand with strtol/strtod
// (exact token checks and file:line messages, which stream extraction does not give).
#include "iarap/scene/read_constraints.h"

#include "iarap/core/errors.h"

#include "line_tokens.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace iarap {
namespace {

using detail::parse_coordinate;
using detail::parse_index;
using detail::tokens_of;
using detail::where;

struct Parsed {
  int line;
  Eigen::Vector3d target;
  double weight; // 0: hard
};

// A point on a face: b FACE B0 B1 B2 X Y Z [W].
struct ParsedFacePoint {
  int line;
  int face;
  Eigen::Vector3d barycentric, target;
  double weight; // 0: hard
};

double parse_weight(const std::string& token, const std::string& at) {
  const double W = parse_coordinate(token, at, "weight");
  if (!(W > 0)) throw InputError(at + "weight " + token + " must be > 0 (a soft constraint's W)");
  return W;
}

// b FACE B0 B1 B2 X Y Z [W] (tokens[0] == "b").
ParsedFacePoint parse_face_point(const std::vector<std::string>& tokens, const std::string& at, int line,
                                 int num_faces) {
  if (tokens.size() != 8 && tokens.size() != 9)
    throw InputError(at +
                     "expected 'b face b0 b1 b2 x y z' (hard) or 'b face b0 b1 b2 x y z w' (soft), found " +
                     std::to_string(tokens.size()) + " token(s)");
  errno = 0;
  char* end = nullptr;
  const long long face = std::strtoll(tokens[1].c_str(), &end, 10);
  if (end == tokens[1].c_str() || *end != '\0' || errno == ERANGE)
    throw InputError(at + "bad face index '" + tokens[1] + "' (expected a non-negative integer)");
  if (face < 0 || face >= num_faces)
    throw InputError(at + "face index " + tokens[1] + " out of range; the mesh has " +
                     std::to_string(num_faces) + " faces");
  ParsedFacePoint p{line, static_cast<int>(face), {}, {}, 0.0};
  p.barycentric << parse_coordinate(tokens[2], at, "b0 barycentric"),
      parse_coordinate(tokens[3], at, "b1 barycentric"), parse_coordinate(tokens[4], at, "b2 barycentric");
  if (std::abs(p.barycentric.sum() - 1.0) > 1e-9) {
    std::ostringstream sum;
    sum.precision(12); // enough to show an error above 1e-9
    sum << p.barycentric.sum();
    throw InputError(at + "barycentric coordinates sum to " + sum.str() + ", not 1 (within 1e-9)");
  }
  p.target << parse_coordinate(tokens[5], at, "x"), parse_coordinate(tokens[6], at, "y"),
      parse_coordinate(tokens[7], at, "z");
  p.weight = tokens.size() == 9 ? parse_weight(tokens[8], at) : 0.0;
  return p;
}

} // namespace

ConstraintSet parse_constraints(std::istream& in, const std::string& source, int num_vertices,
                                int num_faces) {
  std::vector<int> order; // vertex indices in order of first appearance
  std::unordered_map<int, Parsed> seen;
  std::vector<ParsedFacePoint> face_points;
  ConstraintSet result;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    const auto tokens = tokens_of(text);
    if (tokens.empty()) continue;
    const std::string at = where(source, line);
    if (tokens[0] == "b") {
      face_points.push_back(parse_face_point(tokens, at, line, num_faces));
      continue;
    }
    // 'index x y' is a target in the plane z = 0 (a planar mesh).
    if (tokens.size() < 3 || tokens.size() > 5) {
      throw InputError(
          at +
          "expected 'index x y z' (hard; 'index x y' in the plane z = 0), 'index x y z w' (soft) "
          "or 'b face b0 b1 b2 x y z [w]', found " +
          std::to_string(tokens.size()) + " token(s)");
    }
    const long long index = parse_index(tokens[0], at);
    if (index < 0 || index >= num_vertices) {
      throw InputError(at + "vertex index " + tokens[0] + " out of range; the mesh has " +
                       std::to_string(num_vertices) + " vertices (valid: 0.." +
                       std::to_string(num_vertices - 1) + ")");
    }
    const Eigen::Vector3d target(parse_coordinate(tokens[1], at, "x"), parse_coordinate(tokens[2], at, "y"),
                                 tokens.size() >= 4 ? parse_coordinate(tokens[3], at, "z") : 0.0);
    const double weight = tokens.size() == 5 ? parse_weight(tokens[4], at) : 0.0;
    const int vertex = static_cast<int>(index);
    const auto found = seen.find(vertex);
    if (found == seen.end()) {
      seen.emplace(vertex, Parsed{line, target, weight});
      order.push_back(vertex);
    } else if (weight > 0 || found->second.weight > 0) {
      throw InputError(at + "vertex " + std::to_string(vertex) + " already constrained at line " +
                       std::to_string(found->second.line) +
                       (weight > 0 && found->second.weight > 0 ? " (soft)" : "") +
                       "; a vertex takes one constraint, hard or soft");
    } else if (found->second.target == target) {
      result.warnings.push_back(at + "vertex " + std::to_string(vertex) + " repeats line " +
                                std::to_string(found->second.line) + " with the same target; merged");
    } else {
      throw InputError(at + "vertex " + std::to_string(vertex) + " already constrained at line " +
                       std::to_string(found->second.line) + " to a different target");
    }
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(line));
  if (order.empty() && face_points.empty())
    throw InputError(source + ": no constraints (expected lines 'index x y z')");
  std::vector<int> hard, soft;
  for (const int v : order) (seen.at(v).weight > 0 ? soft : hard).push_back(v);
  result.fixed.resize(static_cast<Eigen::Index>(hard.size()));
  result.targets.resize(static_cast<Eigen::Index>(hard.size()), 3);
  for (std::size_t k = 0; k < hard.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    result.fixed(row) = hard[k];
    result.targets.row(row) = seen.at(hard[k]).target.transpose();
    result.origins.push_back(source + ":" + std::to_string(seen.at(hard[k]).line));
  }
  SoftConstraintSet& s = result.soft;
  std::vector<ParsedFacePoint> soft_points, hard_points;
  for (const ParsedFacePoint& p : face_points) (p.weight > 0 ? soft_points : hard_points).push_back(p);
  const auto ns = static_cast<Eigen::Index>(soft.size()), nb = static_cast<Eigen::Index>(soft_points.size());
  s.vertices.resize(ns);
  s.vertex_weights.resize(ns);
  s.vertex_targets.resize(ns, 3);
  for (Eigen::Index k = 0; k < ns; ++k) {
    const Parsed& p = seen.at(soft[static_cast<size_t>(k)]);
    s.vertices(k) = soft[static_cast<size_t>(k)];
    s.vertex_weights(k) = p.weight;
    s.vertex_targets.row(k) = p.target.transpose();
    s.origins.push_back(source + ":" + std::to_string(p.line));
  }
  s.faces.resize(nb);
  s.barycentric.resize(nb, 3);
  s.face_weights.resize(nb);
  s.face_targets.resize(nb, 3);
  for (Eigen::Index k = 0; k < nb; ++k) {
    const ParsedFacePoint& p = soft_points[static_cast<size_t>(k)];
    s.faces(k) = p.face;
    s.barycentric.row(k) = p.barycentric.transpose();
    s.face_weights(k) = p.weight;
    s.face_targets.row(k) = p.target.transpose();
    s.origins.push_back(source + ":" + std::to_string(p.line));
  }
  const auto nh = static_cast<Eigen::Index>(hard_points.size());
  s.hard_faces.resize(nh);
  s.hard_barycentric.resize(nh, 3);
  s.hard_targets.resize(nh, 3);
  for (Eigen::Index k = 0; k < nh; ++k) {
    const ParsedFacePoint& p = hard_points[static_cast<size_t>(k)];
    s.hard_faces(k) = p.face;
    s.hard_barycentric.row(k) = p.barycentric.transpose();
    s.hard_targets.row(k) = p.target.transpose();
    s.origins.push_back(source + ":" + std::to_string(p.line));
  }
  return result;
}

ConstraintSet read_constraints(const std::string& path, int num_vertices, int num_faces) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open constraints file");
  return parse_constraints(in, path, num_vertices, num_faces);
}

} // namespace iarap
