// Soft constraints of ARAP (issue 32): weighted pulls of vertices, or of points on faces given by
// barycentric coordinates, toward targets. Unlike the hard constraints (the fixed set of arap_precompute),
// the soft vertices stay free unknowns: the solver minimizes
//
//   E_total(U) = E_ARAP(U) + P(U),   P(U) = sum_k W_k ||c_k^T U - t_k||^2
//
// with E_ARAP = sum_e sum_{c in cells(e)} (w_e / 2) ||U^T b_e - R_c s_hat_e||^2 (arap_energy), c_k the #V
// vector of point k (e_i for soft vertex i; B0, B1, B2 at the corners a, b, c of its face) and t_k its target
// (no factor 1/2 in front of W: the penalty of a vertex at distance d from its target is W d^2). Since
// E_ARAP = U^T L U / 2 - ... with L = sum_e |cells(e)| w_e b_e b_e^T (Eq. 17), the system matrix of the
// global step becomes L + Q with Q = sum_k 2 W_k c_k c_k^T (2 W on the diagonal of a soft vertex) and the
// right-hand side gains sum_k 2 W_k c_k t_k^T. Q's entries lie on the diagonal or on the edges of a face,
// inside L's pattern: the symbolic analysis of the system does not depend on the weights.
//
// Hard point constraints (hard_faces, hard_barycentric) ask c_k^T U = t_k exactly. They are eliminated on
// the factorized system by a Schur complement of the Lagrange (KKT) system, not by a null-space basis: the
// factor of (L + Q)_ff is the one every solve already has, and a few dense columns Y = (L + Q)_ff^{-1} C^T
// correct each solve onto the constraints (x -= Y S^{-1} (C x - d), S = C Y), while a null-space basis of C
// would change the sparse system and need a factorization of its own. Each hard point also enters Q with an
// internal weight kHardPointWeight: that term vanishes, with its gradient, wherever the point is on its
// target, so it does not move the constrained minimizer, but it keeps (L + Q)_ff positive definite on a
// component held by hard points only. A point that repeats others (its row of C a combination of theirs)
// is dropped when its target agrees with theirs, and refused otherwise (HardPointConflict).
#pragma once
#include "iarap/core/errors.h"

#include <Eigen/Core>

#include <string>

namespace iarap {

struct ArapSoftConstraints {
  Eigen::VectorXi vertices;         // #sv soft vertices (0-based; not also in the fixed set)
  Eigen::VectorXd vertex_weights;   // #sv weights W > 0, finite
  Eigen::VectorXi faces;            // #sb faces (0-based rows of F) of the point constraints
  Eigen::MatrixXd barycentric;      // #sb x 3 coordinates (B0, B1, B2) over F.row(face), summing to 1
  Eigen::VectorXd face_weights;     // #sb weights W > 0, finite
  Eigen::VectorXi hard_faces;       // #hb faces (0-based rows of F) of the hard point constraints
  Eigen::MatrixXd hard_barycentric; // #hb x 3 coordinates over F.row(hard_faces(k)), summing to 1

  // The number of points, #sv + #sb + #hb: the rows of the soft targets of arap_solve (soft vertices
  // first, then the soft face points, then the hard ones, each in the order above).
  Eigen::Index size() const { return vertices.size() + faces.size() + hard_faces.size(); }
  // The weighted ones, #sv + #sb (the rows of the penalty).
  Eigen::Index soft_size() const { return vertices.size() + faces.size(); }
};

// The weight with which a hard point also enters Q (see above). L's entries are scale-free (cotangent
// weights, and iARAP's w |e| / |s| ratios), typically 1 to 10 on the diagonal, and so is this weight.
constexpr double kHardPointWeight = 1.0;

// Thrown by arap_solve when hard point `point` (0-based in hard_faces) cannot hold together with the hard
// points `others` before it and the fixed vertices: its row of C is a combination of theirs but its target
// is off theirs by `gap` (mesh units). Callers that know where the points came from can name them.
class HardPointConflict : public InputError {
public:
  HardPointConflict(Eigen::Index point_index, Eigen::Index other_index, double gap_length,
                    const std::string& message)
      : InputError(message), point(point_index), other(other_index), gap(gap_length) {}
  Eigen::Index point; // the later of the two
  Eigen::Index other; // the earlier hard point it contradicts with the largest share, or -1: the fixed
                      // vertices alone
  double gap;
};

} // namespace iarap
