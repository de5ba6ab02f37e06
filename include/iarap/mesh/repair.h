// Opt-in repair of what check_mesh reports: unwelded copies of a vertex, unreferenced vertices, zero-area
// and duplicate faces, non-manifold edges and vertices, inconsistently oriented faces. Vertex order is
// kept for the vertices that stay; vertices split apart are appended after them.
#pragma once
#include "iarap/mesh/weld_representatives.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

struct RepairOptions {
  bool weld = true;              // merge vertices closer than weld_tolerance * bbox diagonal
  double weld_tolerance = 1e-12; // relative to the bounding-box diagonal; 0 merges identical positions only
  bool remove_unreferenced = true;
  // Faces with area <= 1e-12 * bbox_diagonal^2, and faces that repeat a vertex (in the input, not by
  // welding: those are always removed).
  bool remove_zero_area = false;
  bool remove_duplicate_faces = true; // faces on the same three vertices as an earlier face, either way round
  // Separate the faces of each edge with 3 or more faces into manifold sheets (flattest pairs stay joined)
  // and give a vertex one copy per fan of faces where a closed fan touches another fan or a separated edge
  // ends (split_non_manifold.h in src/mesh says how).
  bool split_non_manifold = true;
  // Also split vertices where only open fans meet (sheets touching at a point): ARAP handles those as one
  // rotation cell, keeping the sheets joined there, so by default they stay.
  bool split_open_fans = false;
  // Reverse faces so that each orientable piece (faces joined across two-face edges) is consistently
  // oriented, keeping the orientation most of its faces have; a non-orientable piece (Moebius strip) is
  // left as it is and counted, and check_mesh then names it.
  bool orient = true;
};

// What repair_mesh changed, by kind.
struct RepairCounts {
  int welded_vertices = 0;       // vertices merged onto a coincident one
  int collapsed_faces = 0;       // faces welding left with a repeated vertex (removed)
  int repeated_vertex_faces = 0; // faces of the input that repeat a vertex (removed with remove_zero_area)
  int zero_area_faces = 0;       // removed
  int duplicate_faces = 0;       // removed
  int split_edges = 0;           // non-manifold edges separated into sheets
  int split_vertices = 0;        // vertices given copies (one per fan or sheet)
  int vertex_copies = 0;         // the copies added
  int flipped_faces = 0;         // faces reversed to agree with their piece
  int non_orientable_pieces = 0; // left as they are
  int unreferenced_vertices = 0; // removed
};

// Calls visit(name, value) for every count, in the order above: the one list the front-ends' reports (the
// repair command's JSON, Python's dict) are written from.
template <class Visit> void visit_repair_counts(const RepairCounts& c, Visit&& visit) {
  visit("welded_vertices", c.welded_vertices);
  visit("collapsed_faces", c.collapsed_faces);
  visit("repeated_vertex_faces", c.repeated_vertex_faces);
  visit("zero_area_faces", c.zero_area_faces);
  visit("duplicate_faces", c.duplicate_faces);
  visit("split_edges", c.split_edges);
  visit("split_vertices", c.split_vertices);
  visit("vertex_copies", c.vertex_copies);
  visit("flipped_faces", c.flipped_faces);
  visit("non_orientable_pieces", c.non_orientable_pieces);
  visit("unreferenced_vertices", c.unreferenced_vertices);
}

struct RepairResult {
  Eigen::MatrixXd V; // #V_new x 3: the vertices that stay in input order, then the copies of split ones
  Eigen::MatrixXi F; // #F_new x 3: the faces that stay, in input order
  // #V_old: new index of each old vertex (its weld target's; for a split vertex the copy that keeps the
  // first fan, which is the vertex's own position in the order), -1 where removed.
  Eigen::VectorXi old_to_new;
  // #V_new: the old vertex each new one stands for (a weld target, or the vertex a copy was split from);
  // several new vertices share one old vertex where it was split.
  Eigen::VectorXi new_to_old;
  RepairCounts counts;
  std::vector<std::string> actions; // one line per kind of change made (or left), with counts
};

// Welding keeps the smallest index of each cluster. The steps run in the order of the options: weld,
// remove faces, split, orient, drop unreferenced vertices. A split copy sits exactly at its vertex's
// position. Throws InputError when V is not #V x 3, F not #F x 3, or a face index is out of range.
RepairResult repair_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                         const RepairOptions& options = {});

} // namespace iarap
