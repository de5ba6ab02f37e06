// The Laplace-Beltrami operators compared in paper Section 6 (Table 3), selected by kind.
//
// Sign convention (as mesh/cotan.h): every operator is -Delta, #V x #V, L(i,j) = -w_ij for i != j and
// zero row sums, so a symmetric one with positive weights is positive semi-definite.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/laplacian/mass_matrix.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace iarap {

enum class LaplacianKind {
  Cotan,       // extrinsic cotan Laplacian of the input mesh
  Intrinsic,   // cotan Laplacian of the intrinsic Delaunay triangulation (Bobenko-Springborn)
  Iarap,       // L = B^T D_w B of the iARAP global step (Eq. 17)
  IarapPlus,   // L+, the asymmetric first-segment finite-volume operator (end of Section 6)
  IarapSym,    // iARAP energy restricted to the first segment from each end (last remark of Section 6)
  IarapRefined // B^T D_w B of the boundary-robust iARAP (refine_boundary, not in the paper): segments of
               // the triangulation whose obtuse boundary edges were split; still over the input vertices
};

// "cotan", "intrinsic", "iarap", "iarap-plus", "iarap-sym", "iarap-refined". Throws InputError naming the
// unknown word.
LaplacianKind parse_laplacian_kind(const std::string& name);
std::string laplacian_kind_name(LaplacianKind kind);
// Every kind, in the order above.
const std::vector<LaplacianKind>& all_laplacian_kinds();

// The operator of the given kind for V (#V x 3) and F (#F x 3). Kinds other than Cotan need the
// intrinsic Delaunay triangulation of (V, F): pass it as precomputed (it must have been computed from
// this V and F, without refine_boundary: inserted points are not mesh vertices) or it is computed here
// with default options. Throws InputError when precomputed does
// not match (V, F), TopologyError from intrinsic_delaunay.
Eigen::SparseMatrix<double> laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, LaplacianKind kind,
                                      const IntrinsicDelaunay* precomputed = nullptr);

} // namespace iarap
