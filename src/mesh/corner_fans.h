// Internal: the fans of faces around each vertex, per corner 3 g + k of a face list G (#G x 3, three
// distinct in-range indices per face). Two corners of one vertex are in the same fan when their faces
// meet across an edge at that vertex; which faces of an edge meet is a "sheet" of the edge: all of them
// for check_mesh (a non-manifold edge joins its faces into one fan), a pair of them where repair_mesh
// separates a non-manifold edge into manifold sheets.
#pragma once
#include "iarap/mesh/edge_topology.h"

#include <Eigen/Core>
#include <vector>

namespace iarap::mesh_checks {

// Edge slot 3 g + k is edge t.FE(g, k) as face g sees it. sheet[slot] in 0..sheet_count-1: the faces
// whose slots share a sheet meet across that edge. Returns the fan of each corner (0..#fans-1, numbered in
// order of each fan's first corner).
Eigen::VectorXi corner_fans(const Eigen::MatrixXi& G, const EdgeTopology& t, const std::vector<int>& sheet,
                            int sheet_count);

// Every face of an edge meets every other: sheet = the edge.
Eigen::VectorXi corner_fans(const Eigen::MatrixXi& G, const EdgeTopology& t);

// The vertices of G (#G x 3 over num_vertices) where more than one fan of corner_fans(G, t) meets,
// increasing: `open` where every fan there is open (ends on two boundary edges; sheets touching at a point),
// `closed` where a closed fan touches another.
struct PinchedVertices {
  std::vector<int> open, closed;
};
PinchedVertices pinched_vertices(const Eigen::MatrixXi& G, const EdgeTopology& t, int num_vertices);

} // namespace iarap::mesh_checks
