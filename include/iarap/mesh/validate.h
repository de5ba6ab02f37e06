// Validation of a triangle mesh before ARAP: what is wrong with it, what cannot be handled, what repair
// fixes.
#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace iarap {

struct MeshReport {
  int vertices = 0, faces = 0;
  int components = 0; // pieces of the faces connected through shared vertices (unused vertices not counted)
  int boundary_loops = 0; // connected chains of boundary edges
  // Per component chi = V - E + F and genus = (2 - chi - b) / 2, summed; null when the mesh is non-manifold
  // or a component is non-orientable.
  std::optional<int> genus;
  // Components whose faces admit no consistent orientation (Moebius strip, Klein bottle), found by
  // propagating orientations across manifold edges, not from the parity of the Euler characteristic.
  int non_orientable_components = 0;
  bool orientable() const { return non_orientable_components == 0; }
  int non_manifold_edges = 0;    // edges with 3 or more faces
  int non_manifold_vertices = 0; // vertices whose faces form more than one edge-connected fan
  int zero_area_faces = 0;       // degenerate faces (is_degenerate_face)
  int unreferenced_vertices = 0;
  int non_delaunay_edges = 0;            // interior edges with cot a + cot b < -1e-12 (negative cotan weight)
  int inconsistently_oriented_edges = 0; // interior edges both faces traverse in the same direction
  int repeated_vertex_faces = 0;
  int out_of_range_indices = 0;   // face entries outside 0..#V-1
  int non_finite_coordinates = 0; // vertices with a NaN or Inf coordinate
  int coincident_vertices = 0;    // vertices within 1e-12 * bbox_diagonal of a vertex with a smaller index
  int boundary_edges = 0;
  int edges = 0;                             // distinct edges of the faces that enter the topological checks
  double bbox_diagonal = 0.0;                // of the finite vertices
  std::vector<std::string> errors, warnings; // each names the first offending element and the count
  // How many of the errors say only that the mesh is not an oriented manifold: non-manifold edges, closed
  // fans touching another fan at a vertex, mixed orientation, non-orientable. Tools that need a manifold
  // refuse those; ARAP deforms such a mesh as it is (iARAP on its tufted cover, docs/nonmanifold.md).
  int oriented_manifold_errors = 0;
  bool usable() const { return errors.empty(); }
  // Usable for ARAP deformation without repair: every error is one of oriented_manifold_errors.
  bool deformable() const { return static_cast<int>(errors.size()) == oriented_manifold_errors; }
};

// Checks V (#V x 3) and F (#F x 3). Never throws on bad data and never reads out of bounds: faces with
// out-of-range indices or repeated vertices are reported and left out of the topological checks.
// Errors: non-finite coordinates, out-of-range indices, faces with repeated vertices, no faces, wrong column
// counts (nothing can handle these); non-manifold edges or vertices, inconsistent orientation (ARAP deforms
// these on the tufted cover; counted in oriented_manifold_errors).
// Warnings (repair_mesh fixes): unreferenced vertices, zero-area faces, coincident vertices, one component
// per face. O(#F log #F + #V log #V).
MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Length of the diagonal of the bounding box of the finite rows of V (#V x 3); 0 when there are none.
double bounding_box_diagonal(const Eigen::MatrixXd& V);

// A face whose cotangent weights ARAP cannot use: area <= 1e-12 x bbox_diagonal^2 from its corners, or edge
// lengths that make no triangle in double precision (the cotangents from the lengths, as the elements
// compute them, are not finite: a needle 1e-10 high on a unit base rounds its two short sides to exactly
// half the base). check_mesh counts these as zero-area faces and repair_mesh (remove_zero_area) drops them,
// so that both agree with what the precompute refuses. False for a face with a non-finite corner (an error
// of its own).
bool is_degenerate_face(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c,
                        double bbox_diagonal);

// What `iarap deform` needs beyond the defaults to run on a usable mesh with each method: a flag, why, and
// the methods ("arap", "spokes-rims", "iarap") that refuse the mesh without it. `info` prints these; a test
// over dirty and shared meshes keeps them equal to what the precompute does.
struct DeformNeed {
  std::string flag;
  std::string why;
  std::vector<std::string> methods;
};
std::vector<DeformNeed> deform_needs(const MeshReport& report);

} // namespace iarap
