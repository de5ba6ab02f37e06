// Internal: the intrinsic triangulation as a corner table with signpost angles (Sharp, Soliman & Crane
// 2019, "Navigating intrinsic triangulations").
//
// Why signposts: flipping needs only edge lengths, and one angle per halfedge (its direction at its tail
// vertex, measured in the surface's own angle around that vertex) is enough to trace every intrinsic
// edge over the input mesh afterwards, edge by edge and in parallel. Integer coordinates (Gillespie et al.
// 2021) are more robust for very long edges but need far more machinery; an explicit overlay (Fisher et
// al. 2007) must be updated at every flip. The tracer checks every edge's end, so a signpost failure is
// reported, not hidden.
//
// Layout: halfedge h = 3 f + k runs from corner k to corner k+1 of face f and is opposite corner k+2.
// There are no halfedges outside the surface: twin = -1 marks a boundary edge.
#pragma once
#include "iarap/mesh/edge_topology.h"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace iarap::detail {

// The next and previous halfedge of h's face (h >= 0): one remainder, no second one to wrap around.
inline int next_halfedge(int h) {
  return h % 3 == 2 ? h - 2 : h + 1;
}
inline int prev_halfedge(int h) {
  return h % 3 == 0 ? h + 2 : h - 1;
}

struct SignpostTriangulation {
  int num_vertices = 0; // input vertices followed by inserted ones
  int num_input_vertices = 0;
  std::vector<int> corner_vertex;       // 3F vertex at corner h (tail of halfedge h)
  std::vector<int> twin;                // 3F opposite halfedge, -1 on boundary
  std::vector<int> edge;                // 3F edge of halfedge
  std::vector<int> edge_halfedge;       // #E one halfedge of each edge (the one whose tail is E(e,0))
  std::vector<int> edge_vertex;         // 2 #E endpoints (E(e,0), E(e,1)) = (smaller, larger): edge-ordered
                                        // passes read them without chasing edge_halfedge into face arrays
  std::vector<double> length;           // #E intrinsic length
  std::vector<double> phi;              // 3F direction of halfedge h at its tail, in [0, vertex_angle_sum)
  std::vector<double> vertex_angle_sum; // #V total angle around each vertex (Theta_v)
  std::vector<char> boundary_vertex;    // #V
  std::vector<int> original_edge;       // #E input edge this edge still is, -1 once flipped
  // Per halfedge, kept up to date by flips and splits so that Delaunay tests, flips and the export never
  // recompute them: the corner angle at the tail of h inside its face, and the cotangent of the angle
  // opposite h. (Recomputing them took a third of the preprocess on large meshes: one atan2 per corner.)
  std::vector<double> angle; // 3F
  std::vector<double> cot;   // 3F
  double mollify_delta = 0.0;
  // Inserted vertex v = num_input_vertices + q lies on input boundary halfedge inserted_halfedge[q] at
  // parameter inserted_t[q] from its tail: a fixed barycentric point, not a degree of freedom.
  std::vector<int> inserted_halfedge;
  std::vector<double> inserted_t;

  int tail(int h) const { return corner_vertex[static_cast<size_t>(h)]; }
  int head(int h) const { return corner_vertex[static_cast<size_t>(next_halfedge(h))]; }
  double halfedge_length(int h) const { return length[static_cast<size_t>(edge[static_cast<size_t>(h)])]; }
  // Recomputes angle[] and cot[] of face f's three halfedges from the current lengths, from one area.
  void update_face_geometry(int f);
  // Recomputes cot[] only (flips update angle[] themselves).
  void update_face_cotangents(int f);
  int num_faces() const { return static_cast<int>(corner_vertex.size() / 3); }
  int num_edges() const { return static_cast<int>(length.size()); }
};

// The outgoing halfedges of each vertex of the input triangulation in increasing signpost angle (CSR):
// where the tracer finds the input face that holds a direction. Not kept up to date by flips.
// One record per entry (angle and halfedge side by side): the tracer's lookups are random, so each costs
// one cache miss instead of two.
struct VertexFans {
  // Left uninitialized when default-constructed (as the solver's CellEntry): the build writes every entry,
  // and zeroing them first would cost a pass over 16 bytes per halfedge.
  struct Entry {
    Entry() {}
    Entry(double phi_, int halfedge_) : phi(phi_), halfedge(halfedge_) {}
    double phi; // signpost angle, increasing within a vertex
    int halfedge;
  };
  std::vector<int> start;   // #V + 1
  std::vector<Entry> entry; // 3F
};

// What the build reads of the input before it flips anything, for a caller that needs part of it too and
// computes it once (arap_precompute: the topology for the pattern of L, the cotangents for the cotan
// Laplacian, while the build runs beside). Shared pointers, so that each reader drops its reference when
// it is done (peak memory).
struct SignpostInput {
  std::shared_ptr<const EdgeTopology> topology; // edge_topology(F, #V)
  std::shared_ptr<const Eigen::MatrixXd> C;     // #F x 3 face_cotangents(V, F), bit for bit: C(f, k) is the
                                                // cotangent at corner k, from the unmollified lengths
  std::vector<double> length;                   // #E SignpostTriangulation::length before mollification
  std::vector<double> angle;                    // 3F SignpostTriangulation::angle before mollification
};

// Checks (V, F) as the build does (InputError for a bad index or coordinate, TopologyError for a face
// repeating a vertex) and computes the SignpostInput. Non-finite entries of C mark degenerate faces.
SignpostInput signpost_input(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                             bool room_for_boundary_splits);

// Builds the triangulation of the input mesh: validates manifoldness and orientation (TopologyError
// naming the edge or vertex), computes edge lengths (mollified if asked and needed), vertex angle sums and
// the signpost angles of the input halfedges. Edge ids equal those of edge_topology(F). `fans` receives the
// vertex fans, which the angle sweep visits in order anyway. With `room_for_boundary_splits`, the arrays
// get capacity for one split per boundary edge, so that refine_obtuse_boundary does not reallocate them.
// `input`, when given, is signpost_input(V, F, room_for_boundary_splits): the build takes its angles and
// drops its references instead of computing them again.
SignpostTriangulation build_signpost_triangulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                   bool mollify, double mollify_epsilon, VertexFans& fans,
                                                   bool room_for_boundary_splits = false,
                                                   SignpostInput* input = nullptr);

// The same for a surface whose edges are given by their halfedges rather than by vertex pairs (the tufted
// cover, where two edges may join the same two vertices): twin (3F) pairs each halfedge with the halfedge
// running the other way along the same edge (-1: boundary). Edges are numbered by their lowest halfedge.
// Throws TopologyError when twin is not an involution between opposite halfedges, or where a closed fan
// meets another at a vertex.
SignpostTriangulation build_glued_signpost_triangulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                         const std::vector<int>& twin, bool mollify,
                                                         double mollify_epsilon, VertexFans& fans);

// The unflipped input as the tracer and the boundary refinement read it. The tracer's walk jumps between
// faces at random, so each halfedge is one record (a face's three records share one or two cache lines)
// rather than four arrays: tail, twin, length and corner angle each cost a cache miss otherwise.
struct InputTriangulation {
  struct Halfedge { // uninitialized when default-constructed, like VertexFans::Entry
    Halfedge() {}
    Halfedge(int tail_, int twin_, double length_, double angle_)
        : tail(tail_), twin(twin_), length(length_), angle(angle_) {}
    int tail;
    int twin; // -1 on the boundary
    double length;
    double angle; // interior angle at the tail
  };
  std::vector<Halfedge> halfedge; // 3F, same numbering as SignpostTriangulation
  std::vector<int> edge_halfedge; // #E

  const Halfedge& operator[](int h) const { return halfedge[static_cast<size_t>(h)]; }
  int tail(int h) const { return (*this)[h].tail; }
  int head(int h) const { return (*this)[next_halfedge(h)].tail; }
  int num_faces() const { return static_cast<int>(halfedge.size() / 3); }
};
InputTriangulation input_triangulation(const SignpostTriangulation& unflipped);

// Flips edge e in place; false (and no change) when the edge cannot be flipped: boundary, both sides in
// one face, or a non-convex intrinsic quad.
bool flip_edge(SignpostTriangulation& tri, int e);

struct FlipStats {
  long flips = 0;
  int non_delaunay_before = 0;
  int non_delaunay_after = 0;
};

// Flips until every interior edge satisfies cot a + cot b >= -tolerance (Bobenko & Springborn 2007).
// With `seeds`, only those edges are checked at the start: the caller guarantees every other edge passes
// (e.g. the edges of the faces a local change touched); non_delaunay_before then counts failing seeds.
FlipStats flip_to_delaunay(SignpostTriangulation& tri, double tolerance,
                           const std::vector<int>* seeds = nullptr);

// Number of interior edges with cot a + cot b < -tolerance.
int count_non_delaunay(const SignpostTriangulation& tri, double tolerance);

struct RefineStats {
  int inserted = 0;
  int rounds = 0;
  long flips = 0;
  int obtuse_before = 0; // boundary edges with an obtuse opposite angle before refinement
  int obtuse_after = 0;
};

// Boundary edges whose one opposite angle is obtuse (cot < -tolerance), i.e. a negative cotan weight.
int count_obtuse_boundary_edges(const SignpostTriangulation& tri, double tolerance);

// Splits each boundary edge with an obtuse opposite angle at the foot of the altitude from the opposite
// vertex (both new opposite angles are then acute), re-flips to Delaunay, and repeats until no boundary
// edge is obtuse or `max_insertions` is reached. `input` is the unflipped input triangulation, which
// locates each inserted point on its input boundary edge. Returns what it did.
RefineStats refine_obtuse_boundary(SignpostTriangulation& tri, const InputTriangulation& input,
                                   double tolerance, int max_insertions);

} // namespace iarap::detail
