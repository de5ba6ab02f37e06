// Unique undirected edges of a triangle mesh and the face/edge incidences, as flat arrays.
#pragma once
#include <Eigen/Core>

namespace iarap {

struct EdgeTopology {
  Eigen::MatrixXi E;  // #E x 2 vertex indices, E(e,0) < E(e,1)
  Eigen::MatrixXi FE; // #F x 3 edge opposite corner k of face f, i.e. edge (F(f,(k+1)%3), F(f,(k+2)%3))
  Eigen::MatrixXi
      EF; // #E x 2 the (up to) two faces of edge e; -1 where absent; a third face means non-manifold
  Eigen::MatrixXi EK; // #E x 2 corner index (0..2) of the opposite corner in EF(e,0/1); -1 where absent
  Eigen::VectorXi face_count; // #E number of faces incident to edge e (3+ = non-manifold)
};

// Builds the edge topology of F (#F x 3, indices into #V vertices). Edges with more than two faces keep
// the first two in EF and count all of them in face_count. Edges are ordered by (E(e,0), E(e,1)), the
// faces of an edge by (face, corner). O(#F log(max valence) + #V): linear at bounded valence, never
// quadratic in a vertex of huge valence.
EdgeTopology edge_topology(const Eigen::MatrixXi& F, int num_vertices);

} // namespace iarap
