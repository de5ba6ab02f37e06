#include "writer_support.h"
#include "../mesh/face_index_range.h"

#include "iarap/core/errors.h"

#include <charconv>

namespace iarap::io_detail {

void check_mesh_arrays(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3) throw InputError(path + ": V has " + std::to_string(V.cols()) + " columns; 3 needed");
  if (F.cols() != 3) throw InputError(path + ": F has " + std::to_string(F.cols()) + " columns; 3 needed");
  require_face_indices_in_range(F, V.rows(), path + ": ");
}

void append_double(std::string& out, double x) {
  // Same text as printf("%.17g") (checked on 2M random bit patterns, NaN, Inf, subnormals), several times
  // faster.
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, 17);
  out.append(buffer, end);
}

void append_int(std::string& out, long long i) {
  char buffer[24];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, i);
  out.append(buffer, end);
}

void append_vertex_lines(std::string& out, const Eigen::MatrixXd& V, const char* prefix) {
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    out += prefix;
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_double(out, V(v, k));
    }
    out += '\n';
  }
}

void append_face_lines(std::string& out, const Eigen::MatrixXi& F, const char* prefix, int index_base) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    out += prefix;
    for (int k = 0; k < 3; ++k) {
      if (k > 0) out += ' ';
      append_int(out, static_cast<long long>(F(f, k)) + index_base);
    }
    out += '\n';
  }
}

} // namespace iarap::io_detail
