// As-rigid-as-possible deformation with the three energies of the paper: original ARAP (Eq. 1),
// spokes-and-rims (Eq. 2) and intrinsic ARAP (Eq. 9), by local/global block descent (Sec. 4.2).
//
// Set up once, solve often (libigl style):
//   ArapData data = arap_precompute(V, F, fixed);          // elements, L, factorization of L_ff
//   Eigen::MatrixXd U = V;                                  // initial guess
//   ArapReport report = arap_solve(data, targets, U);       // U now holds the deformation
// New targets for the same fixed set reuse the factorization; arap_set_fixed refactorizes.
// The types (ArapMethod, ArapOptions, ArapData, ArapSolveOptions, ArapReport, ...) are in arap_types.h.
#pragma once
#include "iarap/solver/arap_types.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace iarap {

// Builds the elements of options.method on the rest mesh (V #V x 3, F #F x 3, a manifold triangle mesh),
// assembles L and factorizes L_ff for the constrained vertices `fixed` (#fixed, 0-based). A planar mesh
// (V #V x 2, or #V x 3 in the plane z = 0 with ArapOptions::planar) is deformed in its plane with 2x2
// rotations (planar_rotation): the result is the 3D solver's on the mesh embedded at z = 0 wherever no cell
// is squeezed through a reflection, with z exactly 0.
// Throws InputError (bad shapes, face indices, non-finite V, bad fixed set: see arap_set_fixed),
// TopologyError (non-manifold edge, degenerate face without mollification), SolverError (a component
// without constrained vertex, failed factorization).
ArapData arap_precompute(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapOptions& options = {});

// Replaces the constrained set and refactorizes L_ff only. Throws InputError for an empty set, an index
// out of range or a duplicate (naming the position and the index), SolverError for a connected component
// without constrained vertex (naming the component id, its vertex count and one vertex) unless
// pin_unconstrained_components. On a throw, data keeps its previous constrained set.
void arap_set_fixed(ArapData& data, const Eigen::VectorXi& fixed);

// Runs local/global iterations. targets: #fixed x 3 positions of data.fixed (same order); for planar data
// #fixed x 2, or x 3 with z = 0 (InputError naming the row otherwise). U: #V x 3 (planar: #V x 2 or x 3),
// in: the initial guess (its constrained rows are overwritten by the targets first; warm starts pass the
// previous solution), out: the result. Plain iteration k: rhs from the rotations fitted to U_{k-1}
// (Eq. 16), U_k,f = L_ff^{-1}(rhs_f - L_fc U_c), then the local step on U_k gives E(U_k) and the rotations
// for the next iteration. Since L_ff (U_k,f - U_{k-1,f}) = -g_{k-1} this is gradient descent preconditioned
// by L_ff, which options.accelerator speeds up (ArapSolveOptions). data.R holds the rotations of the
// returned U (while the solve runs, U and data.R are kept in the iterations' own vertex order,
// ArapElements::visit_order: an on_iteration callback should not read them). Throws InputError for a wrong
// targets / U shape or a non-finite entry (naming the row), negative max_iterations or window, a NaN
// tolerance or a negative or NaN gradient_tolerance; SolverError when the energy becomes non-finite.
ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                      const ArapSolveOptions& options = {});

// E(U) = min_R sum_e sum_{c in cells(e)} (w_e / 2) ||U^T b_e - R_c s_hat_e||^2 for U #V x 3 (planar data:
// #V x 2 or x 3 in the plane, R_c rotations about z).
double arap_energy(const ArapData& data, const Eigen::MatrixXd& U);

// Per-cell energies of U (they sum to arap_energy), e.g. for colour maps: #V entries, one per vertex, then
// (iARAP with refine_boundary only) one per inserted boundary point.
Eigen::VectorXd arap_cell_energy(const ArapData& data, const Eigen::MatrixXd& U);

// dE/dU (shaped as U) = L U - rhs(R*(U)) with R*(U) the optimal rotations (Eq. 14; the envelope theorem makes
// it the gradient of the minimized energy).
Eigen::MatrixXd arap_gradient(const ArapData& data, const Eigen::MatrixXd& U);

// The cell rotations fitted to the last iterate of arap_solve (identity after arap_precompute): #V, one
// per vertex, then (iARAP with refine_boundary only) one per inserted boundary point.
const std::vector<Eigen::Matrix3d>& arap_rotations(const ArapData& data);

// The #V x #V system matrix L of the global step.
const Eigen::SparseMatrix<double>& arap_system_matrix(const ArapData& data);

// Which factorization L_ff got (CHOLMOD LLT, or LDLT when L_ff is not positive definite).
FactorizationKind arap_factorization(const ArapData& data);

} // namespace iarap
