// Lumped (diagonal) mass matrices: the area of each vertex's cell, on the input or the intrinsic mesh.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace iarap {

enum class MassKind {
  Barycentric, // a third of each incident triangle's area
  Voronoi // mixed Voronoi cells (Meyer et al. 2003): circumcentric, half/quarter splits on obtuse triangles
};

// Lumped areas as per-triangle contributions, from the side lengths: l (#F x 3) holds the length of the
// side opposite corner k of face f, F (#F x 3) the corners' vertices. Returns #V areas. Corners of one
// face at the same vertex (intrinsic Delta-complexes) add up.
Eigen::VectorXd lumped_vertex_areas(const Eigen::MatrixXi& F, const Eigen::MatrixXd& l, int num_vertices,
                                    MassKind kind);

// #V x #V diagonal mass matrix of (V, F). With intrinsic == true the cells are those of the intrinsic
// Delaunay triangulation (precomputed when given, else computed here). Throws InputError when a face
// index is out of range or precomputed does not match (V, F).
Eigen::SparseMatrix<double> mass_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, MassKind kind,
                                        bool intrinsic = false,
                                        const IntrinsicDelaunay* precomputed = nullptr);

// The mass matrices offered by name (Python's iarap.mass_matrix): "voronoi" (mixed Voronoi cells of the
// input mesh, the usual partner of the cotan Laplacian), "barycentric" (a third of each triangle),
// "intrinsic" (mixed Voronoi cells of the intrinsic Delaunay triangulation, the partner of the
// intrinsic and iARAP Laplacians). All are positive on a mesh without zero-area faces and sum to its area.
struct MassMatrixChoice {
  MassKind kind = MassKind::Voronoi;
  bool intrinsic = false;
};
// Throws InputError naming the unknown word and the valid ones.
MassMatrixChoice parse_mass_kind(const std::string& name);
// "voronoi", "barycentric", "intrinsic", in this order.
const std::vector<std::string>& mass_kind_names();

} // namespace iarap
