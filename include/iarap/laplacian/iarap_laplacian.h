// The system matrix of the iARAP global step, L = B^T D_w B (paper Eq. 17).
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/SparseCore>

namespace iarap {

// #V x #V, L = B^T D_w B with B the #S x #V segment matrix (row s = b_s^T, Eq. 8) and
// D_w = diag(w_ij sigma_s) (Eq. 11). Symmetric, PSD (w_ij >= 0 on the intrinsic Delaunay mesh),
// nonzero only between vertices of a common input face. Equals the cotan Laplacian when every
// intrinsic edge is an input edge (one segment, sigma = 1).
// Measured (tests/laplacian): on non-Delaunay meshes too, flat or curved, L equals the extrinsic cotan
// Laplacian to round-off (1e-14 relative on bunny, fertility, flipped grids; an independent hand
// construction on flipped quads agrees to 1e-15): the traced-segment quadrature of the PL interpolant
// reproduces its Dirichlet energy. iARAP differs from original ARAP in its rotations, not in this matrix.
Eigen::SparseMatrix<double> iarap_laplacian(const Segments& segments, int num_vertices);

} // namespace iarap
