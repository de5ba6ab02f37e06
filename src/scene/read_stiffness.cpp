#include "iarap/scene/read_stiffness.h"

#include "iarap/core/errors.h"

#include "line_tokens.h"

#include <fstream>
#include <vector>

namespace iarap {

Eigen::VectorXd parse_stiffness(std::istream& in, const std::string& source, int num_vertices) {
  Eigen::VectorXd stiffness = Eigen::VectorXd::Ones(num_vertices);
  std::vector<int> line_of(static_cast<size_t>(num_vertices), 0);
  const int count = detail::for_each_vertex_line(
      in, source, num_vertices, 2, "index s",
      [&](int index, const std::vector<std::string>& tokens, const std::string& at, int line) {
        int& first = line_of[static_cast<size_t>(index)];
        if (first != 0)
          throw InputError(at + "vertex " + tokens[0] + " already has a stiffness (line " +
                           std::to_string(first) + ")");
        const double s = detail::parse_coordinate(tokens[1], at, "stiffness");
        if (!(s > 0))
          throw InputError(at + "stiffness " + tokens[1] + " of vertex " + tokens[0] + " is not > 0");
        stiffness(index) = s;
        first = line;
      });
  if (count == 0) throw InputError(source + ": no stiffness (expected lines 'index s')");
  return stiffness;
}

Eigen::VectorXd read_stiffness(const std::string& path, int num_vertices) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open stiffness file");
  return parse_stiffness(in, path, num_vertices);
}

} // namespace iarap
