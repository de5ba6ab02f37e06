// Internal: the tufted cover of a triangle mesh (Sharp & Crane 2020, "A Laplacian for Nonmanifold Triangle
// Meshes", Sec. 4.1), an oriented closed surface that every triangle mesh has, manifold or not, orientable
// or not.
//
// Why: the intrinsic Delaunay triangulation needs a surface where every edge has two sides. The cover
// doubles each face f into a front copy 2f = (a, b, c) and a back copy 2f + 1 = (a, c, b); around an input
// edge with k faces, the 2k face-sides are glued in pairs, each side to the nearest side across the empty
// wedge between two faces in angular order (a boundary edge glues a face's front to its own back). The
// cover's vertices are the input's split per fan of the glued faces, so the signpost code sees a manifold
// (a Delta-complex: two cover edges may join the same two vertices). On a clean closed oriented mesh the
// cover is two copies of the mesh (front and back), so each quantity the cover gives is counted twice.
#pragma once
#include "iarap/mesh/edge_topology.h"

#include <Eigen/Core>
#include <vector>

namespace iarap::detail {

struct TuftedCover {
  Eigen::MatrixXi F;      // 2#F x 3 cover faces over cover vertices: 2f front of input face f, 2f + 1 back
  std::vector<int> twin;  // 6#F halfedge 3 g + k (corner k -> k + 1 of cover face g) glued to twin[.]
  Eigen::VectorXi vertex; // #cover vertices: the input vertex each one copies
  Eigen::MatrixXd V;      // #cover vertices x 3 positions, V_input(vertex, :)
  int max_edge_faces = 0; // most faces on one input edge (3 and more: a fin)
};

// The input face a cover face copies.
inline int input_face(int cover_face) {
  return cover_face / 2;
}

// Builds the cover of (V, F) with edge topology `topology` = edge_topology(F, #V). F must have three
// distinct in-range vertices per face (the caller checked). Vertices in no face have no copy.
TuftedCover tufted_cover(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const EdgeTopology& topology);

// True when (F, topology) is an oriented manifold as the signpost build takes it: at most two faces per
// edge, the two traversing it in opposite directions, and no vertex where a closed fan of faces meets
// another fan (open fans meeting at a vertex, sheets touching at a point, are accepted).
bool is_oriented_manifold(const Eigen::MatrixXi& F, const EdgeTopology& topology, int num_vertices);

// True when every edge has at most two faces and two faces traverse their edge in opposite directions.
bool edges_are_oriented_manifold(const Eigen::MatrixXi& F, const EdgeTopology& topology);

// On edges that are an oriented manifold (edges_are_oriented_manifold): true when the faces at every
// vertex form one fan (open or closed). False where some vertex has several fans, or where an edge breaks
// the premise.
bool every_vertex_has_one_fan(const Eigen::MatrixXi& F, const EdgeTopology& topology, int num_vertices);

} // namespace iarap::detail
