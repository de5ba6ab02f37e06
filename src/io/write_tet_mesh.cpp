#include "iarap/io/write_tet_mesh.h"

#include "iarap/core/errors.h"

#include "atomic_file.h"
#include "file_extension.h"
#include "writer_support.h"

namespace iarap {

bool is_tet_mesh_output_path(const std::string& path) {
  return io_detail::lower_extension(path) == ".mesh";
}

void write_tet_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  if (!is_tet_mesh_output_path(path))
    throw InputError(path + ": unsupported tetrahedral mesh extension '" + io_detail::lower_extension(path) +
                     "' for writing (writable: .mesh)");
  if (V.cols() != 3) throw InputError(path + ": V has " + std::to_string(V.cols()) + " columns; 3 needed");
  if (T.cols() != 4) throw InputError(path + ": T has " + std::to_string(T.cols()) + " columns; 4 needed");
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k)
      if (T(t, k) < 0 || T(t, k) >= V.rows())
        throw InputError(path + ": tetrahedron " + std::to_string(t) + " uses vertex " +
                         std::to_string(T(t, k)) + "; the mesh has " + std::to_string(V.rows()) +
                         " vertices");
  std::string out;
  out.reserve(static_cast<std::size_t>(V.rows() * 62 + T.rows() * 32 + 64));
  out += "MeshVersionFormatted 2\nDimension 3\nVertices\n";
  io_detail::append_int(out, V.rows());
  out += '\n';
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      io_detail::append_double(out, V(v, k));
      out += ' ';
    }
    out += "0\n";
  }
  out += "Tetrahedra\n";
  io_detail::append_int(out, T.rows());
  out += '\n';
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    for (int k = 0; k < 4; ++k) {
      io_detail::append_int(out, T(t, k) + 1);
      out += ' ';
    }
    out += "0\n";
  }
  out += "End\n";
  io_detail::write_file_atomically(path, out);
}

} // namespace iarap
