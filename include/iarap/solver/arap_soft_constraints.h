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
#pragma once
#include <Eigen/Core>

namespace iarap {

struct ArapSoftConstraints {
  Eigen::VectorXi vertices;       // #sv soft vertices (0-based; not also in the fixed set)
  Eigen::VectorXd vertex_weights; // #sv weights W > 0, finite
  Eigen::VectorXi faces;          // #sb faces (0-based rows of F) of the point constraints
  Eigen::MatrixXd barycentric;    // #sb x 3 coordinates (B0, B1, B2) over F.row(face), summing to 1
  Eigen::VectorXd face_weights;   // #sb weights W > 0, finite

  // The number of soft points, #sv + #sb: the rows of the soft targets of arap_solve (vertices first, then
  // the face points, each in the order above).
  Eigen::Index size() const { return vertices.size() + faces.size(); }
};

} // namespace iarap
