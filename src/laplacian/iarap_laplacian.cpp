#include "iarap/laplacian/iarap_laplacian.h"

#include "iarap/core/errors.h"

#include <string>

namespace iarap {

Eigen::SparseMatrix<double> iarap_laplacian(const Segments& segments, int num_vertices) {
  const Eigen::SparseMatrix<double>& B = segments.B;
  if (B.cols() != num_vertices || segments.weight.size() != B.rows())
    throw InputError("segments do not match the mesh: B is " + std::to_string(B.rows()) + " x " +
                     std::to_string(B.cols()) + ", " + std::to_string(segments.weight.size()) + " weights, " +
                     std::to_string(num_vertices) + " vertices");
  // Eq. 17: L = B^T D_w B, B (#S x #V) holding b_s^T per row, D_w = diag(w_ij sigma_s) (Eq. 11).
  const Eigen::SparseMatrix<double> D_w_B = segments.weight.asDiagonal() * B;
  return Eigen::SparseMatrix<double>(B.transpose() * D_w_B);
}

} // namespace iarap
