// Connected components of the vertices of a triangle mesh (through shared faces).
#pragma once
#include <Eigen/Core>

namespace iarap {

// component(v) in 0..count-1 for every vertex v < num_vertices; a vertex no face uses is its own
// component. Components are numbered in order of their smallest vertex index.
Eigen::VectorXi vertex_components(const Eigen::MatrixXi& F, int num_vertices, int* count = nullptr);

} // namespace iarap
