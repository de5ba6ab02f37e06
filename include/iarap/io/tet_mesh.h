// Tetrahedral meshes: what the tet readers return, and the checks they and arap_precompute_tets share.
//
// Orientation: a tetrahedron (a, b, c, d) is positive when det(b - a, c - a, d - a) > 0 (TetGen 1.5's .ele
// output is; not every writer's is), so the readers orient each file as a whole: all negative -> every
// tetrahedron reoriented (c and d swapped, a note says so); mixed signs -> an error naming the first
// tetrahedron of the rarer sign (a tangled or corrupted mesh; reorienting it one by one would hide that). The
// ARAP energy itself does not depend on the order of a tetrahedron's vertices.
#pragma once
#include <Eigen/Core>

#include <string>
#include <vector>

namespace iarap {

struct TetMesh {
  Eigen::MatrixXd V;              // #V x 3 positions, in file order
  Eigen::MatrixXi T;              // #T x 4 vertex indices (0-based), positive volume
  std::vector<std::string> notes; // what the reader changed: reoriented tetrahedra, skipped elements
};

// det(b - a, c - a, d - a) / 6 for every row (a, b, c, d) of T (#T x 4, indices not checked): #T.
Eigen::VectorXd tet_signed_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// The first bad tetrahedron of (V #V x 3, T #T x 4), or tet = -1 when there is none. message names it as
// "tetrahedron k (a, b, c, d) ...": an index out of 0..#V-1, a vertex used twice, or zero volume
// (|volume| <= 1e-12 x the mean edge length of T cubed). Shapes and finiteness are the caller's checks.
struct TetProblem {
  Eigen::Index tet = -1;
  std::string message;
};
TetProblem find_tet_problem(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);

// The boundary of T: the faces used by exactly one tetrahedron, in the order of their tetrahedra (#B x 3),
// oriented outward when the tetrahedra are positive (as the readers return them). Indices are T's
// (interior vertices stay in V, unreferenced by the faces). A face used by three or more tetrahedra is not
// boundary.
Eigen::MatrixXi tet_boundary_faces(const Eigen::MatrixXi& T);

} // namespace iarap
