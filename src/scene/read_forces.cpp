#include "iarap/scene/read_forces.h"

#include "iarap/core/errors.h"

#include "line_tokens.h"

#include <fstream>

namespace iarap {

Eigen::MatrixXd parse_forces(std::istream& in, const std::string& source, int num_vertices) {
  Eigen::MatrixXd forces = Eigen::MatrixXd::Zero(num_vertices, 3);
  std::string text;
  int line = 0, count = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const auto hash = text.find('#'); hash != std::string::npos) text.erase(hash);
    const auto tokens = detail::tokens_of(text);
    if (tokens.empty()) continue;
    const std::string at = detail::where(source, line);
    if (tokens.size() != 4)
      throw InputError(at + "expected 'index fx fy fz', found " + std::to_string(tokens.size()) +
                       " token(s)");
    const long long index = detail::parse_index(tokens[0], at);
    if (index < 0 || index >= num_vertices)
      throw InputError(at + "vertex index " + tokens[0] + " out of range; the mesh has " +
                       std::to_string(num_vertices) + " vertices (valid: 0.." +
                       std::to_string(num_vertices - 1) + ")");
    forces.row(static_cast<Eigen::Index>(index)) += Eigen::RowVector3d(
        detail::parse_coordinate(tokens[1], at, "fx"), detail::parse_coordinate(tokens[2], at, "fy"),
        detail::parse_coordinate(tokens[3], at, "fz"));
    ++count;
  }
  if (in.bad()) throw InputError(source + ": read error after line " + std::to_string(line));
  if (count == 0) throw InputError(source + ": no forces (expected lines 'index fx fy fz')");
  return forces;
}

Eigen::MatrixXd read_forces(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open forces file");
  return parse_forces(in, path, num_vertices);
}

} // namespace iarap
