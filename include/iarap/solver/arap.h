// As-rigid-as-possible deformation with the three energies of the paper: original ARAP (Eq. 1),
// spokes-and-rims (Eq. 2) and intrinsic ARAP (Eq. 9), by local/global block descent (Sec. 4.2).
//
// Set up once, solve often (libigl style):
//   ArapData data = arap_precompute(V, F, fixed);          // elements, L, factorization of L_ff
//   Eigen::MatrixXd U = V;                                  // initial guess
//   ArapReport report = arap_solve(data, targets, U);       // U now holds the deformation
// New targets for the same fixed set reuse the factorization; arap_set_fixed refactorizes.
// Soft constraints (arap_soft_constraints.h: weighted vertices and points on faces, E_total = E_ARAP + P):
//   ArapData data = arap_precompute(V, F, fixed, soft);             // factorizes (L + Q)_ff
//   ArapReport report = arap_solve(data, targets, soft_targets, U);  // new soft targets: no refactorization
//   arap_set_soft_weights(data, vertex_weights, face_weights);      // numeric refactorization only
// Hard points on faces (ArapSoftConstraints::hard_faces) go in the same struct, their targets last in
// soft_targets; arap_solve keeps them exactly (throws HardPointConflict for contradictory ones).
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
// Throws InputError (bad shapes, face indices, non-finite V, bad fixed set: see arap_set_fixed, a bad
// ArapOptions::stiffness: see check_arap_stiffness, bad ArapOptions::rigid_groups: see check_rigid_groups
// and rigid_groups.h),
// TopologyError (non-manifold edge, degenerate face without mollification), SolverError (a component
// without constrained vertex, failed factorization).
ArapData arap_precompute(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapOptions& options = {});

// Throws InputError unless stiffness has n entries, each finite and > 0, naming the first bad vertex.
void check_arap_stiffness(const Eigen::VectorXd& stiffness, Eigen::Index n);

// The same with soft constraints: L_ff becomes (L + Q)_ff (arap_soft_constraints.h). fixed may then be
// empty, and a connected component needs a fixed vertex or a soft point, not both. Throws InputError as
// above and for bad soft constraints (naming the entry: a vertex out of range or also fixed, a face out of
// range, a weight that is not finite and > 0, barycentric coordinates not finite or not summing to 1 within
// 1e-9, lengths that differ).
ArapData arap_precompute(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& fixed,
                         const ArapSoftConstraints& soft, const ArapOptions& options = {});

// New weights for data.soft's points (vertex_weights #sv, face_weights #sb): Q and the numeric
// factorization of (L + Q)_ff change, the symbolic analysis is kept (Q lies in L's pattern). Throws
// InputError for a bad weight or length (data unchanged), SolverError when the factorization fails (data's
// factorization is then empty).
void arap_set_soft_weights(ArapData& data, const Eigen::VectorXd& vertex_weights,
                           const Eigen::VectorXd& face_weights);

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
// returned U (while the solve runs, data.R is kept in the iterations' own vertex order,
// ArapElements::visit_order, and U is empty, its rows held in that order: an on_iteration callback should
// not read them). Throws InputError for a wrong targets / U shape or a non-finite entry (naming the
// row), negative max_iterations or window, a NaN tolerance or a negative or NaN gradient_tolerance,
// rotation smoothing with rigid groups (and targets that move a group's constrained vertices off a rigid
// motion); SolverError when the energy becomes non-finite.
// (Throws InputError when data has soft constraints: their targets are the next function's.)
ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, Eigen::MatrixXd& U,
                      const ArapSolveOptions& options = {});

// The same minimizing E_ARAP + P with soft_targets (data.soft.size() x 3, planar x 2: vertex points first,
// then face points) the targets of data.soft's points; report.energies are of the total, report.penalty and
// report.arap_energy its two parts at the returned U. New soft targets reuse the factorization. Throws as
// above, and InputError for a wrong soft_targets shape or a non-finite row.
ArapReport arap_solve(ArapData& data, const Eigen::MatrixXd& targets, const Eigen::MatrixXd& soft_targets,
                      Eigen::MatrixXd& U, const ArapSolveOptions& options = {});

// P(U) = sum_k W_k ||c_k^T U - t_k||^2 for data.soft (0 without soft constraints); U #V x 3.
double arap_penalty(const ArapData& data, const Eigen::MatrixXd& soft_targets, const Eigen::MatrixXd& U);

// dP/dU (shaped as U) = sum_k 2 W_k c_k (c_k^T U - t_k): add arap_gradient for that of the total.
Eigen::MatrixXd arap_penalty_gradient(const ArapData& data, const Eigen::MatrixXd& soft_targets,
                                      const Eigen::MatrixXd& U);

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
// The report of a solve run on a mesh divided by s (normalizing_scale), in the mesh's own units: energies
// (initial, per iteration, penalty, potential, arap_energy) times s^2, gradient norms and Newton's trust
// radius and reference gradient (the L_ff norm of a displacement) times s.
void rescale_report(ArapReport& report, double s);

FactorizationKind arap_factorization(const ArapData& data);

} // namespace iarap
