#include "iarap/mesh/connected_components.h"

#include "disjoint_sets.h"

#include <vector>

namespace iarap {

Eigen::VectorXi vertex_components(const Eigen::MatrixXi& F, int num_vertices, int* count) {
  detail::DisjointSets sets(num_vertices);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 1; k < 3; ++k) sets.join(F(f, 0), F(f, k));
  Eigen::VectorXi component(num_vertices);
  std::vector<int> label(static_cast<size_t>(num_vertices), -1);
  int n = 0;
  for (int v = 0; v < num_vertices; ++v) {
    const int r = sets.find(v);
    if (label[r] < 0) label[r] = n++;
    component(v) = label[r];
  }
  if (count) *count = n;
  return component;
}

} // namespace iarap
