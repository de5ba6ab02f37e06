// Internal: the named checks check_mesh composes, one per property (as libigl's is_edge_manifold and
// is_vertex_manifold). Each counts its defect in the report and adds one message naming the first
// offending element and, where repair_mesh fixes it, the repair; none throws or reads out of bounds. The
// topological checks see only the faces with three distinct in-range indices (CheckedFaces).
#pragma once
#include "iarap/mesh/edge_topology.h"
#include "iarap/mesh/validate.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap::mesh_checks {

struct CheckedFaces {
  Eigen::MatrixXi G;     // #G x 3: the faces of F with three distinct in-range indices, in order
  std::vector<int> face; // #G: the row of F of each
};

// "1 vertex has" / "2 vertices have".
std::string plural(int n, const char* one, const char* many);
// "; repair_mesh <what> (RepairOptions::<option>)": the library's repair, which front-ends rename.
std::string repair_hint(const char* what, const char* option);
// "edge (a, b)" for edge e of t.
std::string edge_name(const EdgeTopology& t, int e);
// Connected groups of the pairs (a_i, b_i) over n items (vertex_components on degenerate "faces").
Eigen::VectorXi group_pairs(const std::vector<int>& a, const std::vector<int>& b, int n, int* count);

// Coordinates (V is #V x 3): NaN or Inf; vertices within 1e-12 x bbox diagonal of an earlier one.
void check_finite_coordinates(const Eigen::MatrixXd& V, MeshReport& r);
void check_coincident_vertices(const Eigen::MatrixXd& V, MeshReport& r);

// Face indices (F is #F x 3): entries outside 0..#V-1; faces repeating a vertex; vertices no face with
// in-range indices uses; and the faces the topological checks see.
void check_index_range(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r);
void check_repeated_vertices(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r);
void check_unreferenced_vertices(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r);
CheckedFaces checked_faces(const Eigen::MatrixXi& F, int num_vertices);

// Faces of area <= 1e-12 x bbox diagonal^2 (r.bbox_diagonal in the units of V).
void check_zero_area_faces(const Eigen::MatrixXd& V, const CheckedFaces& faces, MeshReport& r);

// Edges: boundary and non-manifold (3 or more faces) edges; interior edges with a negative cotan weight;
// interior edges whose faces run the same way, and components with no consistent orientation.
void check_edge_manifold(const EdgeTopology& t, MeshReport& r);
void count_non_delaunay_edges(const Eigen::MatrixXd& V, const CheckedFaces& faces, const EdgeTopology& t,
                              MeshReport& r);
void check_orientation(const CheckedFaces& faces, const EdgeTopology& t, MeshReport& r);

// Vertices whose faces form more than one edge-connected fan: a warning where every fan is open, else an
// error.
void check_vertex_manifold(const CheckedFaces& faces, const EdgeTopology& t, int num_vertices, MeshReport& r);

// Components, boundary loops and (orientable manifolds only, so after the checks above) the genus; a
// warning when every face is a component of its own (a triangle soup).
void check_components(const CheckedFaces& faces, const EdgeTopology& t, int num_vertices, MeshReport& r);
void check_face_soup(const CheckedFaces& faces, MeshReport& r);

} // namespace iarap::mesh_checks
