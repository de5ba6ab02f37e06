// The cotan Laplacian of an intrinsic (Delta-complex) triangulation, from its per-edge cotan weights.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/SparseCore>

namespace iarap {

// #V x #V, L(i,j) = -sum of w_e over intrinsic edges e joining i and j (parallel edges add up), zero row
// sums. A loop edge (i == j) contributes w_e (f_i - f_i) = 0 and is skipped.
Eigen::SparseMatrix<double> intrinsic_cotan_laplacian(const IntrinsicTriangulation& T, int num_vertices);

} // namespace iarap
