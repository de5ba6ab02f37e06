// Internal: which faces of G (#G x 3, three distinct in-range indices per face) must be reversed for each
// piece of the surface to be consistently oriented, found by propagating a flip bit face to face across
// the edges with exactly two faces. check_mesh counts the pieces where no choice works (Moebius strip,
// Klein bottle); repair_mesh reverses the faces the bits name.
#pragma once
#include "iarap/mesh/edge_topology.h"

#include <Eigen/Core>
#include <vector>

namespace iarap::mesh_checks {

struct FaceOrientation {
  std::vector<char> flip;       // #G: 1 where the face runs against the first face of its piece
  std::vector<int> piece;       // #G: the piece (faces joined across two-face edges), 0.., in face order
  std::vector<char> orientable; // per piece: whether the bits agree across every two-face edge
  int non_orientable = 0;       // pieces that are not orientable
  int first_conflict = -1;      // a face of the first non-orientable piece where the bits disagree
};

// t is edge_topology(G, #V). O(#G).
FaceOrientation face_orientation(const Eigen::MatrixXi& G, const EdgeTopology& t);

} // namespace iarap::mesh_checks
