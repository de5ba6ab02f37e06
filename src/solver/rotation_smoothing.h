// Rotation smoothing (issue 45, ArapSolveOptions::rotation_smoothing): the symmetric form of CGAL's SRE_ARAP
// (Levi & Gotsman 2015) as a term on the cells' rotations,
//   E_smooth(R) = (ALPHA A / 2) sum_i (1 / (2 d_i)) sum_{j in N(i)} |R_i - R_j|_F^2
//               = sum_{pairs i~j} k_ij |R_i - R_j|_F^2,   k_ij = (ALPHA A / 2) (1 / (2 d_i) + 1 / (2 d_j)),
// A the total rest area, N(i) the cells that share an element with cell i (original ARAP: the mesh edges;
// spokes-and-rims: the vertices of i's faces, the same one-ring; iARAP: the intrinsic Delaunay edges), d_i =
// |N(i)|. The 1/2 in ALPHA A / 2: our data terms weigh an element (w_e / 2) per cell (arap_elements.h), half
// CGAL's w_ij per half-edge, so an ALPHA here is CGAL's alpha on the same minimizers.
//
// With it the local step is coupled: minimize over all rotations at once
//   f(R) = -sum_i tr(R_i^T S_i) + E_smooth(R)      (S_i the cell's covariance, Eq. 15)
// Its block minimizer in R_i alone is polar(T_i), T_i = S_i + 2 sum_j k_ij R_j. fit() takes Riemannian
// Newton steps R_i <- R_i exp([omega_i]), halved until f decreases, and falls back to a Gauss-Seidel sweep
// over a colouring of the neighbour graph (cells of one colour are independent: each update is the exact
// block minimizer) when no step does, so f never increases; it stops when the stationarity residual
// g_i = -vee(P_i - P_i^T), P_i = R_i^T T_i, is at rounding. (A cold start begins with one sweep.) The tangent
// Hessian of f (per cell omega, 3 #cells unknowns) is
//   H_ii = tr(P_i) I - sym(P_i),   H_ij = 2 k_ij (Q_ij^T - tr(Q_ij) I),   Q_ij = R_i^T R_j,
// which also gives the rotations' derivative along a change of positions, H omega = vee(R^T dS - dS^T R),
// for the Hessian of the reduced energy (LocalGlobalProblem::hessian_product). Internal to the solver;
// cells are in the visit order of the problem (streamed_layout.h).
#pragma once
#include "iarap/solver/arap_elements.h"

#include <Eigen/Core>

#include <vector>

namespace iarap::detail {

// vee(P - P^T) = (P_21 - P_12, P_02 - P_20, P_10 - P_01): twice the axial vector of P's skew part.
inline Eigen::Vector3d vee_of_skew_part(const Eigen::Matrix3d& P) {
  return {P(2, 1) - P(1, 2), P(0, 2) - P(2, 0), P(1, 0) - P(0, 1)};
}

// M^{-1} for a symmetric M (the tangent systems' tr(P) I - P), its eigenvalues floored at 1e-6 x the
// largest: positive definite even where the energy is not locally convex (far from a minimizer); 0 for M = 0
// (a cell with no signal).
Eigen::Matrix3d floored_inverse(const Eigen::Matrix3d& M);

// A of E_smooth: the total area of the rest mesh's triangles F (#F x 3) on V (#V x 3).
double rest_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

class RotationSmoothing {
public:
  // The neighbour graph of el's cells (two cells are neighbours when an element lists both), renumbered by
  // position (cell id -> visit position, num_cells entries), and k_ij for alpha >= 0 and the rest area.
  // Throws InputError when no element has two cells (tetrahedral ARAP: one rotation per tetrahedron, which
  // shares no element with another).
  RotationSmoothing(const ArapElements& el, const std::vector<int>& position, double alpha, double area);

  // E_smooth(R), summed pair by pair from the differences (accurate as it goes to zero).
  double energy(const std::vector<Eigen::Matrix3d>& R) const;

  // The coupled local step: R (num_cells, visit order) becomes a minimizer of f for the covariances S,
  // starting from R when it holds one rotation per cell (never raising f from there), else from the
  // uncoupled fits polar(S_i). Returns the number of Gauss-Seidel sweeps plus Newton steps taken.
  int fit(const std::vector<Eigen::Matrix3d>& S, std::vector<Eigen::Matrix3d>& R);

  // The tangent Hessian H of f at (S, R) for tangent_solve.
  void prepare_tangent(const std::vector<Eigen::Matrix3d>& S, const std::vector<Eigen::Matrix3d>& R);
  // omega = H^{-1} a (per cell, 3-vectors) by conjugate gradients preconditioned by H's diagonal blocks, to
  // a relative residual of 1e-12 (the Newton iteration's Hessian product must be linear to that accuracy).
  // Returns the CG iterations.
  int tangent_solve(const std::vector<Eigen::Vector3d>& a, std::vector<Eigen::Vector3d>& omega) const;

private:
  Eigen::Matrix3d coupled_target(const std::vector<Eigen::Matrix3d>& S, const std::vector<Eigen::Matrix3d>& R,
                                 int i) const;
  double objective_change(const std::vector<Eigen::Matrix3d>& S, const std::vector<Eigen::Matrix3d>& R,
                          const std::vector<Eigen::Matrix3d>& R_new) const;
  void sweep(const std::vector<Eigen::Matrix3d>& S, std::vector<Eigen::Matrix3d>& R) const;
  // g_i = -vee(P_i - P_i^T); returns max_i |g_i| and sets scale = max_i |T_i|_F.
  double stationarity(const std::vector<Eigen::Matrix3d>& S, const std::vector<Eigen::Matrix3d>& R,
                      std::vector<Eigen::Vector3d>& g, double& scale) const;
  int conjugate_gradients(const std::vector<Eigen::Vector3d>& b, std::vector<Eigen::Vector3d>& x,
                          double tolerance, int max_iterations) const;
  void apply(const std::vector<Eigen::Vector3d>& x, std::vector<Eigen::Vector3d>& y) const;

  int cells_ = 0;
  // Directed neighbour pairs as CSR by visit position: the neighbours of i are neighbour_[start_[i] ..
  // start_[i + 1]) with coupling k_[..] (k_ij = k_ji).
  std::vector<int> start_, neighbour_;
  std::vector<double> k_;
  // The cells of colour c: colour_cell_[colour_start_[c] .. colour_start_[c + 1]).
  std::vector<int> colour_start_, colour_cell_;
  // The tangent Hessian: diagonal blocks, their (floored) inverses, off-diagonal blocks per directed pair.
  std::vector<Eigen::Matrix3d> H_diagonal_, H_diagonal_inverse_, H_off_;
};

} // namespace iarap::detail
