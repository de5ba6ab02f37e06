#include "mesh_checks.h"

namespace iarap::mesh_checks {

void check_edge_manifold(const EdgeTopology& t, MeshReport& r) {
  const int ne = static_cast<int>(t.E.rows());
  r.edges = ne;
  int first = -1;
  for (int e = 0; e < ne; ++e) {
    const int count = t.face_count(e);
    if (count == 1) ++r.boundary_edges;
    if (count > 2 && r.non_manifold_edges++ == 0) first = e;
  }
  if (r.non_manifold_edges == 0) return;
  ++r.oriented_manifold_errors;
  r.errors.push_back(plural(r.non_manifold_edges, "edge is", "edges are") +
                     " non-manifold (3 or more faces); first: " + edge_name(t, first) + " with " +
                     std::to_string(t.face_count(first)) + " faces" +
                     repair_hint("separates their faces into manifold sheets", "split_non_manifold"));
}

} // namespace iarap::mesh_checks
