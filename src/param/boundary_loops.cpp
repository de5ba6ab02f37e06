#include "iarap/param/boundary_loops.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/edge_topology.h"

#include <string>

namespace iarap {

std::vector<std::vector<int>> boundary_loops(const Eigen::MatrixXi& F, int num_vertices) {
  const EdgeTopology topology = edge_topology(F, num_vertices);
  // next[a] = b for every boundary edge a -> b, directed as its one face traverses it.
  std::vector<int> next(static_cast<std::size_t>(num_vertices), -1);
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e) {
    if (topology.face_count(e) != 1) continue;
    const int f = topology.EF(e, 0), k = topology.EK(e, 0);
    const int a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
    int& slot = next[static_cast<std::size_t>(a)];
    if (slot != -1)
      throw TopologyError("vertex " + std::to_string(a) + " starts two boundary edges (to vertices " +
                          std::to_string(slot) + " and " + std::to_string(b) +
                          "): it is non-manifold or its faces disagree in orientation");
    slot = b;
  }
  std::vector<std::vector<int>> loops;
  std::vector<char> visited(next.size(), 0);
  for (int start = 0; start < num_vertices; ++start) {
    if (next[static_cast<std::size_t>(start)] == -1 || visited[static_cast<std::size_t>(start)]) continue;
    std::vector<int> loop;
    int v = start;
    while (!visited[static_cast<std::size_t>(v)]) {
      visited[static_cast<std::size_t>(v)] = 1;
      loop.push_back(v);
      v = next[static_cast<std::size_t>(v)];
      if (v == -1)
        throw TopologyError("the boundary chain from vertex " + std::to_string(start) + " ends at vertex " +
                            std::to_string(loop.back()) + " without closing");
    }
    if (v != start)
      throw TopologyError("the boundary chain from vertex " + std::to_string(start) + " runs into vertex " +
                          std::to_string(v) + " twice: a non-manifold boundary vertex");
    loops.push_back(std::move(loop));
  }
  return loops;
}

} // namespace iarap
