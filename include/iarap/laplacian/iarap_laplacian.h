// The system matrix of the iARAP global step, L = B^T D_w B (paper Eq. 17).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/SparseCore>

namespace iarap {

// #V x #V, L = B^T D_w B with B the #S x #V segment matrix (row s = b_s^T, Eq. 8) and
// D_w = diag(w_ij sigma_s) (Eq. 11). Symmetric, PSD (w_ij >= 0 on the intrinsic Delaunay mesh),
// nonzero only between vertices of a common input face. Equals the cotan Laplacian when every
// intrinsic edge is an input edge (one segment, sigma = 1).
// It is the extrinsic cotan Laplacian of the input mesh on every mesh, Delaunay or not, with boundary or
// boundary refinement, whenever the intrinsic lengths are not mollified: proof in docs/operator-identity.md,
// tests in tests/laplacian/operator_identity_test.cpp (round-off, 8 eps kappa m). iARAP differs from original
// ARAP in its rotations and right-hand side, not in this matrix.
Eigen::SparseMatrix<double> iarap_laplacian(const Segments& segments, int num_vertices);

} // namespace iarap
