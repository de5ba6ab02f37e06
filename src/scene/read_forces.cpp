#include "iarap/scene/read_forces.h"

#include "iarap/core/errors.h"

#include "line_tokens.h"

#include <fstream>

namespace iarap {

Eigen::MatrixXd parse_forces(std::istream& in, const std::string& source, int num_vertices) {
  Eigen::MatrixXd forces = Eigen::MatrixXd::Zero(num_vertices, 3);
  const int count = detail::for_each_vertex_line(
      in, source, num_vertices, 4, "index fx fy fz",
      [&](int index, const std::vector<std::string>& tokens, const std::string& at, int) {
        forces.row(index) += Eigen::RowVector3d(detail::parse_coordinate(tokens[1], at, "fx"),
                                                detail::parse_coordinate(tokens[2], at, "fy"),
                                                detail::parse_coordinate(tokens[3], at, "fz"));
      });
  if (count == 0) throw InputError(source + ": no forces (expected lines 'index fx fy fz')");
  return forces;
}

Eigen::MatrixXd read_forces(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open forces file");
  return parse_forces(in, path, num_vertices);
}

} // namespace iarap
