// The properties of a discrete Laplacian (Wardetzky et al. 2007) measured on one mesh, one row of the
// paper's Table 3.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/laplacian/laplacians.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>

namespace iarap {

struct LaplacianProperties {
  std::string kind;
  bool symmetric = false;    // symmetry_error <= 1e-12
  double symmetry_error = 0; // max |L - L^T| / max |L_ii|
  // Weak: L(i,j) != 0 only for neighbours i, j (input or intrinsic). Strong: in addition every entry
  // depends only on the geometry near i and j. Both measured. Strong locality: for a few probe vertices k
  // (the ones whose input star the most traced intrinsic edges cross, not incident to k, where a global
  // construction would show) V is copied with k moved by 5% of its smallest altitude and the operator is
  // rebuilt from scratch (intrinsic triangulation included); the largest change of an entry (i, j) with i
  // or j outside k's closed input 1-ring is the leak. strongly_local: sparsity within the input 1-rings and
  // every probe's leak <= 1e-9 max |L_ii|. The cotan Laplacian leaks exactly 0 (its entries read only the
  // triangles at the edge); the iARAP operator, equal to it (docs/operator-identity.md), leaks only the
  // round-off of that identity (<= 1e-12); operators that read the intrinsic triangulation leak 1e-4 and up.
  bool weakly_local = false, strongly_local = false;
  int strong_locality_probes = 0;  // 0 when not measured (unknown kind): strongly_local is then false
  double strong_locality_leak = 0; // max over the probes, relative to max |L_ii|
  bool sparsity_within_input_adjacency = false; // measured: nonzeros on input edges and the diagonal
  bool sparsity_within_intrinsic_adjacency =
      false; // measured against intrinsic edges (false when not computed)
  // On a flat mesh (all vertices within 1e-12 * bbox diagonal of a plane): max over interior vertices of
  // |(L x)_i|, |(L y)_i| for in-plane coordinates x, y, over max |L_ii| * bbox diagonal. NaN when not flat.
  double linear_precision_residual = 0;
  bool positive_weights = false;  // no wrong-signed off-diagonal entry
  int negative_offdiag_count = 0; // wrong-signed: L(i,j) > 1e-12 max |L_ii| for i != j (our sign convention)
  double negative_offdiag_max_abs = 0; // the largest such entry
  double negative_offdiag_sum_abs = 0; // their sum
  // Where the wrong-signed entries lie: on input boundary edges, and among those on boundary edges whose
  // opposite angle in the intrinsic Delaunay triangulation is obtuse (negative intrinsic cotan weight,
  // which no flip can remove: boundary edges are never flipped). 0 when no triangulation was given.
  int negative_offdiag_on_boundary = 0;
  int negative_offdiag_on_obtuse_boundary = 0;
  // x^T L x >= 0 for all x, i.e. every eigenvalue of the symmetric part (L + L^T)/2 is >= -1e-9 max |L_ii|:
  // decided exactly by the inertia of an LDL^T factorization of (L + L^T)/2 + 1e-9 max |L_ii| I.
  bool psd = false;
  double min_eigenvalue = 0; // smallest eigenvalue of (L + L^T)/2 (Spectra, shift-invert)
  // Eigenvalues of L itself (they differ from the symmetric part's only for asymmetric L): a Gershgorin
  // lower bound on their real parts, min_i (L_ii - sum_{j != i} |L_ij|) / max |L_ii|; >= 0 proves every
  // eigenvalue has a non-negative real part. min_real_part: the smallest real part among the eigenvalues
  // Spectra finds nearest to a shift below that bound (equals min_eigenvalue when L is symmetric).
  double gershgorin_real_part_bound = 0;
  double min_real_part = 0;
  // The second PSD reading, for asymmetric L: every eigenvalue of L has real part >= -1e-9 max |L_ii|,
  // proven by the Gershgorin bound when it is >= -1e-12, else read from min_real_part.
  bool eigenvalues_nonnegative_real_part = false;
  double row_sum_max_abs = 0;  // max_i |sum_j L_ij| (absolute)
  double diagonal_max_abs = 0; // max |L_ii|, the scale of the relative figures
};

// Measures the properties of L (#V x #V) built for (V, F) with the given kind. V: #V x 3, F: #F x 3.
// idt (the intrinsic Delaunay triangulation of (V, F)) sets the intrinsic adjacency and the obtuse
// boundary edges; when null those readings stay false / 0. Strong locality is measured when kind is a
// laplacian_kind_name (the probes rebuild the operator of that kind), else reported unmeasured.
// Throws SolverError when the eigenvalue solver fails.
LaplacianProperties laplacian_properties(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         const Eigen::SparseMatrix<double>& L, const std::string& kind,
                                         const IntrinsicDelaunay* idt);

// Builds the operator of the given kind (laplacians.h) and measures it.
LaplacianProperties laplacian_properties(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                         LaplacianKind kind, const IntrinsicDelaunay* precomputed = nullptr);

} // namespace iarap
