#include "iarap/mesh/connected_components.h"

#include <numeric>
#include <vector>

namespace iarap {

namespace {
int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]]; // path halving
    x = parent[x];
  }
  return x;
}
} // namespace

Eigen::VectorXi vertex_components(const Eigen::MatrixXi& F, int num_vertices, int* count) {
  std::vector<int> parent(static_cast<size_t>(num_vertices));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, F(f, 0)), b = find_root(parent, F(f, k));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  Eigen::VectorXi component(num_vertices);
  std::vector<int> label(static_cast<size_t>(num_vertices), -1);
  int n = 0;
  for (int v = 0; v < num_vertices; ++v) {
    const int r = find_root(parent, v);
    if (label[r] < 0) label[r] = n++;
    component(v) = label[r];
  }
  if (count) *count = n;
  return component;
}

} // namespace iarap
