// The weighted edge elements shared by the three ARAP energies (paper Eq. 1, 2, 9), as flat arrays.
//
// Every variant is a set of rotation cells (one per vertex) and elements e, each with a sparse
// vector b_e over the input vertices (2 or 3 non-zeros summing to 0), a rest vector s_hat_e = V_rest^T b_e,
// a weight w_e and the cells whose rotation it is compared against:
//   E(V) = min_R sum_e sum_{c in cells(e)} (w_e / 2) || V^T b_e - R_c s_hat_e ||^2.
// (An element seen from its other end has -b and -s_hat; the sign cancels.)
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/mesh/edge_topology.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

namespace iarap {

namespace detail {
struct StreamedLayout;
} // namespace detail

struct ArapElements {
  using IndexRows = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using ValueRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

  int num_vertices = 0; // #V
  // Rotations about the z axis only (planar_rotation): a planar mesh deformed in its plane. arap_precompute
  // sets it for planar data; the builders leave it false.
  bool planar = false;
  int num_cells = 0;           // rotation cells: one per vertex, plus (iARAP with refine_boundary) one per
                               // inserted boundary point, numbered #V, #V + 1, ... as in the triangulation
  IndexRows b_index;           // #E x 3 vertices of b_e; an unused slot repeats slot 0 with value 0
  ValueRows b_value;           // #E x 3 coefficients of b_e (sum 0)
  ValueRows s_hat;             // #E x 3 rest vectors V_rest^T b_e (Eq. 8), summed in slot order like V^T b_e
  Eigen::VectorXd w;           // #E weights; negative where the variant says so (never clamped)
  std::vector<int> face;       // #E an input face holding every non-zero of b_e (system_pattern.h)
  std::vector<int> cell_start; // #E + 1: cells of element e are cell[cell_start[e] .. cell_start[e+1])
  std::vector<int> cell;       // cell (vertex) indices; a cell may repeat (intrinsic loop edges)
  // num_cells + 1: the CSR transpose, the elements of cell c (with repetition) are
  // cell_element[cell_element_start[c] .. cell_element_start[c + 1]).
  std::vector<int> cell_element_start;
  std::vector<int> cell_element;
  // num_cells factors s_c > 0 on each cell's energy (ArapOptions::stiffness), already folded into the
  // streamed layout's weights; empty: 1 everywhere. L weighs element e by (sum over cells(e) of s_c) w_e.
  Eigen::VectorXd cell_stiffness;

  // True once release_element_arrays emptied the per-element arrays above (arap_precompute does unless
  // ArapOptions::keep_elements): only num_vertices, num_cells, planar, cell_stiffness and the streamed
  // layout are left, which is all the iterations read; element_system_matrix then throws.
  bool arrays_released = false;
  // What rotation smoothing needs of the arrays once they are released (release_element_arrays fills it):
  // the other cells that share an element with each cell, cell_neighbour[cell_neighbour_start[c] ..
  // cell_neighbour_start[c + 1]) ascending, and whether any element has two or more cells.
  std::vector<int> cell_neighbour_start;
  std::vector<int> cell_neighbour;
  bool cells_share_elements = false;

  // The same elements regrouped cell by cell in a cache-friendly visit order, as the iterations stream them
  // (internal; every builder fills it, and copies of the elements share it: it is never changed).
  std::shared_ptr<const detail::StreamedLayout> streamed;

  Eigen::Index size() const { return w.size(); }
};

// Frees el's per-element arrays (b_index, b_value, s_hat, w, face, cells and their transpose) and sets
// arrays_released; the streamed layout, the counts and the stiffness stay.
void release_element_arrays(ArapElements& el);

// Checks a rest mesh for the builders: V #V x 3 finite, F #F x 3 with indices in 0..#V-1.
// Throws InputError naming the vertex or the face and index.
void check_arap_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Original ARAP (Eq. 1): one element per undirected mesh edge (i, j), b = e_j - e_i, cells {i, j},
// w_ij = (cot a + cot b) / 2 (one term on boundary edges, the sum over all faces of an edge with more than
// two), negative on non-Delaunay edges. The cell of vertex i is every edge at i, whatever the fans of faces
// there: no manifoldness or orientation needed. Throws TopologyError naming the face when a face is
// degenerate (non-finite cotangent); InputError for bad shapes or face indices.
ArapElements arap_edge_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// The same from what the caller computed once already (arap_precompute): topology = edge_topology(F, #V)
// and C = face_cotangents(V, F) of a mesh that passed check_arap_mesh.
ArapElements arap_edge_elements(const Eigen::MatrixXd& V, const EdgeTopology& topology,
                                const Eigen::MatrixXd& C);

// Spokes-and-rims (Chao et al. 2010, Eq. 2): one element per (face, edge) pair, w = cot(opposite angle) / 2,
// cells = the face's three vertices. Throws TopologyError naming a degenerate face; InputError for bad input.
ArapElements spokes_rims_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
// The same from C = face_cotangents(V, F) computed by the caller, for a mesh that passed check_arap_mesh.
ArapElements spokes_rims_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                  const Eigen::MatrixXd& C);

// iARAP (Eq. 9, 11): one element per segment of a traced intrinsic Delaunay edge, b and w = w_ij |e|/|s|
// from the segments, cells = the two endpoints of the segment's intrinsic edge. s_hat is recomputed as
// V^T b so that the undeformed mesh has exactly zero energy. V is the rest mesh the triangulation was
// built on; zero-length segments (b = 0) are left out. Throws InputError when the segments do not match V
// or the triangulation.
ArapElements iarap_elements(const Eigen::MatrixXd& V, const IntrinsicDelaunay& intrinsic);

// The system matrix of the global step, L = sum_e |cells(e)| w_e b_e b_e^T (#V x #V, Eq. 16-17):
// 2 x cotan Laplacian for original ARAP, 3 x for spokes-and-rims, 2 B^T D_w B for iARAP. Throws InputError
// when the arrays were released (ArapElements::arrays_released).
Eigen::SparseMatrix<double> element_system_matrix(const ArapElements& elements);

} // namespace iarap
