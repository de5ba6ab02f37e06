// What GET /api/intrinsic_edges draws: the rest mesh's intrinsic Delaunay edges traced over the input.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace iarap::serve {

// Intrinsic Delaunay edges traced over the input (TracedEdges, CSR): point p of edge e, for p in
// start[e] .. start[e+1]-1, is (1 - t[p]) U[a[p]] + t[p] U[c[p]] (c = -1: the vertex a[p]).
struct IntrinsicOverlay {
  std::vector<std::int32_t> start, a, c;
  std::vector<float> t;
  std::vector<std::int32_t> original; // #E 1 when the intrinsic edge is still an input edge
};

// intrinsic_delaunay of (V, F) as flat arrays for the client.
IntrinsicOverlay make_intrinsic_overlay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

} // namespace iarap::serve
