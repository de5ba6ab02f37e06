// Intrinsic Delaunay triangulation of a triangle mesh, with every intrinsic edge traced over the
// input mesh as a polyline and cut into segments s = V b (paper Sections 2 and 4, Eq. 7-8, 11).
#pragma once
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace iarap {

struct IntrinsicOptions {
  // An interior edge is flipped while cot(a) + cot(b) < -delaunay_tolerance (a, b its opposite
  // intrinsic angles). Cotangents are scale-free, so the tolerance is dimensionless.
  double delaunay_tolerance = 1e-12;
  // Intrinsic mollification (Sharp & Crane 2020): when some triangle is (nearly) degenerate, every
  // edge length grows by the smallest delta that gives each triangle inequality a margin of
  // mollify_epsilon * mean edge length. delta stays 0 on meshes without such triangles.
  // When false, a degenerate input triangle is a TopologyError naming it.
  bool mollify = true;
  double mollify_epsilon = 1e-6;
  // Boundary-robust iARAP (not in the paper): boundary edges are never flipped, so one whose opposite
  // angle is obtuse keeps a negative weight. With refine_boundary, such an edge is split at the foot of the
  // altitude from its obtuse corner (both new opposite angles are acute), the triangulation re-flipped to
  // Delaunay, and this repeated until no boundary edge is obtuse or max_boundary_insertions points were
  // inserted (-1: 4 x #boundary edges + 100). Inserted points are fixed barycentric points of their input
  // boundary edge, not degrees of freedom; each has its own rotation cell.
  bool refine_boundary = false;
  int max_boundary_insertions = -1;
  // Assemble Segments::B. The ARAP solver sums its system matrix from the segments' b and weights
  // directly and turns this off (B is 12 bytes per non-zero and a sequential counting sort).
  bool assemble_B = true;
  // Return every edge's traced polyline (IntrinsicDelaunay::traces). The segments do not need them: an
  // edge never flipped is its input edge, so the preprocess keeps points of the flipped edges only and
  // builds the segments from those. Off, traces stays empty and the preprocess's peak memory drops by
  // ~20 bytes per edge (the solver and the Laplacians built from segments turn it off).
  bool keep_traces = true;
  // iARAP (arap_precompute) on the tufted cover (Sharp & Crane 2020, docs/nonmanifold.md) even where the
  // input is an oriented manifold. Input that is not one (an edge with 3+ faces, a closed fan touching
  // another at a vertex, mixed orientation, non-orientable) always takes the cover. intrinsic_delaunay()
  // itself works on oriented manifolds only and ignores this.
  bool tufted_cover = false;
};

// The intrinsic triangulation after flipping to Delaunay. In general a Delta-complex: two edges may
// join the same pair of vertices, an edge may be a loop, a face may have two corners at one vertex.
// Everything is therefore indexed by edge and corner, never by vertex pair.
struct IntrinsicTriangulation {
  Eigen::MatrixXi F;             // #F x 3 intrinsic faces (input vertex indices), same count as input
  Eigen::MatrixXi FE;            // #F x 3 intrinsic edge opposite corner k of face f
  Eigen::MatrixXi E;             // #E x 2 endpoints (i, j) of each intrinsic edge; segments run i -> j
  Eigen::VectorXd length;        // #E intrinsic edge lengths |e_ij|
  Eigen::VectorXd cot_weight;    // #E w_ij = (cot a + cot b) / 2, one term on boundary edges
  Eigen::MatrixXd corner_angle;  // #F x 3 intrinsic angle at corner k of face f
  Eigen::VectorXd face_area;     // #F intrinsic face areas
  Eigen::VectorXi is_boundary;   // #E 1 for boundary edges (never flipped), else 0
  Eigen::VectorXi original_edge; // #E the input edge (index into edge_topology(F).E) it still is, or -1
  // Vertices 0 .. num_input_vertices-1 are the input's; vertex num_input_vertices + q is inserted point q
  // (refine_boundary), at (1 - inserted_t(q)) V[inserted_on(q,0)] + inserted_t(q) V[inserted_on(q,1)].
  int num_input_vertices = 0;
  Eigen::MatrixXi inserted_on;    // #P x 2 input boundary edge holding each inserted point
  Eigen::VectorXd inserted_t;     // #P
  int obtuse_boundary_before = 0; // boundary edges with an obtuse opposite angle after flipping
  int obtuse_boundary_after = 0;  // ... and after refinement (0 unless the insertion cap was hit)
  int refine_rounds = 0;
  long flips = 0;
  int non_delaunay_before = 0; // interior edges of the input failing the Delaunay test
  int non_delaunay_after = 0;  // after flipping: 0 unless flips were impossible
  double mollify_delta = 0.0;  // length added to every edge by mollification (0: none)
};

// Traced intrinsic edges: the ordered points of each edge's polyline over the input mesh, in CSR form.
// Point p is (1 - t[p]) * V[a[p]] + t[p] * V[c[p]]: an input vertex (c = -1, t = 0), a crossing of
// input edge (a, c) at parameter t, or (first/last point) an inserted boundary point. face[p] is the input
// face carrying the segment from p to p + 1
// (-1 for the last point of each edge).
struct TracedEdges {
  std::vector<int> start; // #E + 1 offsets into the point arrays
  std::vector<int> a, c, face;
  std::vector<double> t;
};

// The segments of all traced edges (Eq. 7, 8, 11), structure of arrays. The segments of intrinsic
// edge e are rows edge_start[e] .. edge_start[e+1]-1, in order from E(e,0) to E(e,1).
struct Segments {
  Eigen::VectorXi edge;                                           // #S intrinsic edge of each segment
  Eigen::VectorXi face;                                           // #S carrying input face
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> b_index; // #S x 3 input vertices of b
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>
      b_value;                   // #S x 3 coefficients (sum 0; unused slots 0)
  Eigen::MatrixXd s_hat;         // #S x 3 rest vectors V b (Eq. 8)
  Eigen::VectorXd length;        // #S |s| at rest
  Eigen::VectorXd weight;        // #S w_ij |e_ij| / |s| (Eq. 11)
  Eigen::VectorXi edge_start;    // #E + 1 offsets
  Eigen::SparseMatrix<double> B; // #S x #V, row s holds b_s^T; L = B^T D_w B (Eq. 17);
                                 // 0 x 0 when IntrinsicOptions::assemble_B is off
};

struct IntrinsicDelaunay {
  IntrinsicTriangulation triangulation;
  TracedEdges traces; // empty when IntrinsicOptions::keep_traces is off
  Segments segments;
  double flip_ms = 0, trace_ms = 0, segment_ms = 0;
};

// Flips (V, F) to its intrinsic Delaunay triangulation (Bobenko-Springborn), traces every intrinsic
// edge over the input and assembles the segments. V: #V x 3, F: #F x 3, an oriented manifold
// triangle mesh (boundary allowed). Throws TopologyError on non-manifold input or, with
// mollify == false, on a degenerate triangle.
IntrinsicDelaunay intrinsic_delaunay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const IntrinsicOptions& options = {});

} // namespace iarap
