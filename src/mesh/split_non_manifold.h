// Internal: repair_mesh's separation of a non-manifold face list into manifold sheets.
//
// Non-manifold edges (3 or more faces) are separated into sheets: the faces of such an edge are paired
// greedily, two faces of one piece (faces joined across two-face edges) before two of different pieces,
// then the flattest pair first (the two faces whose third vertices lie most nearly opposite across the
// edge), so that a fin or a stray face stuck on a surface comes off it and two planes crossing stay two
// planes; each pair, and each face left over, becomes its own sheet along the edge. Vertices are then
// split into one copy per fan of faces (corners joined across shared sheets): always at the ends of a
// separated edge, and elsewhere where a closed fan (a cone around the vertex, the tip of a closed surface)
// touches another fan. Where only open fans meet, sheets touching at a point as in scans, ARAP handles
// the vertex as it is (one rotation cell), so those stay joined unless split_open_fans. The first fan of a
// vertex (in face order) keeps its index; copies are numbered from #V on, in order of their first corner.
// Faces whose fans still meet around both ends of a separated edge (through other faces) are then cut
// off it: all but the flattest pair get fresh vertices at the edge's ends.
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap::mesh_checks {

struct ManifoldSplit {
  Eigen::MatrixXi F;        // #F x 3, the faces in their order, on the split vertices
  std::vector<int> copy_of; // per new vertex #V + i: the input vertex it is a copy of
  int split_edges = 0;      // non-manifold edges separated into sheets
  int split_vertices = 0;   // input vertices that got one or more copies
};

// V (#V x 3) gives the pairing its geometry; F (#F x 3) has three distinct in-range indices per face.
// O(#F log #F) at bounded valence; an edge with more than max_paired_faces faces (no surface's edge) has
// all its faces separated without pairing, so that no input makes the pairing quadratic.
ManifoldSplit split_non_manifold(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, bool split_open_fans);

constexpr int max_paired_faces = 64;

} // namespace iarap::mesh_checks
