#include "face_index_range.h"

#include "iarap/core/errors.h"

namespace iarap {

std::string out_of_range_face_index(Eigen::Index face, Eigen::Index index, Eigen::Index vertex_count) {
  return "face " + std::to_string(face) + " uses vertex " + std::to_string(index) + "; mesh has " +
         std::to_string(vertex_count) + " vertices";
}

void require_face_indices_in_range(const Eigen::Ref<const Eigen::MatrixXi>& F, Eigen::Index vertex_count,
                                   const std::string& context, Eigen::Index first_face) {
  for (Eigen::Index f = first_face; f < F.rows(); ++f)
    for (Eigen::Index k = 0; k < F.cols(); ++k)
      if (F(f, k) < 0 || F(f, k) >= vertex_count)
        throw InputError(context + out_of_range_face_index(f, F(f, k), vertex_count));
}

void require_triangle_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::string& function) {
  if (V.cols() != 3)
    throw InputError(function + ": V has " + std::to_string(V.cols()) + " columns; 3 needed");
  if (F.cols() != 3)
    throw InputError(function + ": F has " + std::to_string(F.cols()) + " columns; 3 needed");
  require_face_indices_in_range(F, V.rows(), function + ": ");
}

} // namespace iarap
