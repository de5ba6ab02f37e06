// Operators built from the first segment of every intrinsic edge at each of its ends (paper Section 6,
// "Alternative derivation"): the asymmetric L+ and its symmetric energy counterpart.
//
// For vertex i and intrinsic edge e = (i, j) the first segment runs from v_i to the point p where the
// traced edge leaves the star of i: p = (1 - t) v_a + t v_c on the link edge (a, c), or a vertex.
// Its weight is omega = ||*e_ij|| / ||p - v_i|| = w_ij |e_ij| / ||p - v_i||, i.e. the Eq. 11 weight
// sigma w_ij of that segment. When e is an input edge its only segment is the whole edge, p = v_j and
// omega = w_ij: both operators then reduce to the intrinsic cotan weight on that edge.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace iarap {

// L+ (#V x #V): row i = sum over intrinsic edges leaving i of omega (f_i - f_p), f_p interpolated on the
// link. Zero row sums, linear precision on flat meshes (each p lies on the straight edge, so the row is
// the intrinsic Laplacian's), non-positive off-diagonals when all w_ij >= 0, asymmetric.
// Loop edges are skipped: their intrinsic flux w (f_i - f_i) is zero. Throws TopologyError naming the
// edge when a trace is shorter than two points or its first segment has zero length.
Eigen::SparseMatrix<double> iarap_plus_laplacian(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt);

// L_sym (#V x #V) = 1/2 sum over (edge, end) of omega beta beta^T, beta = e_i - (barycentric p), the
// Hessian of the iARAP energy (Eq. 9) with each end keeping only its first segment, at the Eq. 11
// weight: every end carries w_ij/2 as in Eq. 9, so an input edge (both ends share the single segment)
// gets exactly w_ij. Symmetric, PSD, constants in the kernel, input-mesh sparsity, equal to the cotan
// Laplacian on Delaunay meshes. Not linearly precise in general: on a flat mesh row x of L_sym x
// gets -1/2 ||*e|| (v_j - v_x)/|e| from each multi-segment edge at x (half the intrinsic term) plus
// terms from other vertices' first segments that end on x's edges, and nothing cancels them since the
// later segments that telescope them away in Eq. 17 are dropped. The spurious terms come from edges not
// incident to x, so no weight chosen per (edge, end) from local data cancels them; the Eq. 11 weight is
// kept because it makes the operator exact on Delaunay meshes. laplacian_properties measures the loss.
Eigen::SparseMatrix<double> iarap_sym_laplacian(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt);

} // namespace iarap
