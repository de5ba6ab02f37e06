#include "iarap/laplacian/intrinsic_cotan_laplacian.h"

#include <vector>

namespace iarap {

Eigen::SparseMatrix<double> intrinsic_cotan_laplacian(const IntrinsicTriangulation& T, int num_vertices) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(4 * T.E.rows()));
  for (Eigen::Index e = 0; e < T.E.rows(); ++e) {
    const int i = T.E(e, 0), j = T.E(e, 1);
    if (i == j) continue; // a loop's flux w (f_i - f_i) vanishes
    const double w = T.cot_weight(e);
    // Parallel edges between i and j are summed by setFromTriplets.
    triplets.emplace_back(i, j, -w);
    triplets.emplace_back(j, i, -w);
    triplets.emplace_back(i, i, w);
    triplets.emplace_back(j, j, w);
  }
  Eigen::SparseMatrix<double> L(num_vertices, num_vertices);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace iarap
