#include "corner_fans.h"
#include "mesh_checks.h"

#include <algorithm>
#include <utility>

namespace iarap::mesh_checks {

void check_vertex_manifold(const CheckedFaces& faces, const EdgeTopology& t, int num_vertices,
                           MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  const int ng = static_cast<int>(G.rows()), nv = num_vertices;
  const Eigen::VectorXi fan = corner_fans(G, t);
  std::vector<int> fan_of(static_cast<std::size_t>(nv), -1);
  std::vector<char> pinched(static_cast<std::size_t>(nv), 0);
  for (int c = 0; c < 3 * ng; ++c) {
    const int v = G(c / 3, c % 3);
    int& seen = fan_of[static_cast<std::size_t>(v)];
    if (seen < 0)
      seen = fan(c);
    else if (seen != fan(c))
      pinched[static_cast<std::size_t>(v)] = 1;
  }
  // A pinched vertex whose fans are all open (each fan ends on two boundary edges) is where separate
  // sheets touch, common in scans: ARAP keeps one rotation cell there and the intrinsic triangulation gives
  // each fan its own angle range, so it is only a warning. A closed fan touching another is an error.
  std::vector<std::pair<int, int>> vertex_fans;
  for (int c = 0; c < 3 * ng; ++c) {
    const int v = G(c / 3, c % 3);
    if (pinched[static_cast<std::size_t>(v)]) vertex_fans.emplace_back(v, fan(c));
  }
  std::sort(vertex_fans.begin(), vertex_fans.end());
  vertex_fans.erase(std::unique(vertex_fans.begin(), vertex_fans.end()), vertex_fans.end());
  std::vector<int> fan_count(static_cast<std::size_t>(nv), 0), boundary_at(static_cast<std::size_t>(nv), 0);
  for (const auto& vf : vertex_fans) ++fan_count[static_cast<std::size_t>(vf.first)];
  for (int e = 0; e < static_cast<int>(t.E.rows()); ++e)
    if (t.face_count(e) == 1) {
      ++boundary_at[static_cast<std::size_t>(t.E(e, 0))];
      ++boundary_at[static_cast<std::size_t>(t.E(e, 1))];
    }
  const auto all_open = [&](int v) {
    return boundary_at[static_cast<std::size_t>(v)] == 2 * fan_count[static_cast<std::size_t>(v)];
  };
  int first_closed = -1, first_open = -1, open = 0;
  for (int v = 0; v < nv; ++v) {
    if (!pinched[static_cast<std::size_t>(v)]) continue;
    ++r.non_manifold_vertices;
    if (all_open(v)) {
      if (open++ == 0) first_open = v;
    } else if (first_closed < 0) {
      first_closed = v;
    }
  }
  if (open > 0)
    r.warnings.push_back(plural(open, "vertex joins", "vertices join") +
                         " several open fans of faces (sheets touching at a point; handled as one rotation "
                         "cell); first: vertex " +
                         std::to_string(first_open));
  if (r.non_manifold_vertices > open)
    r.errors.push_back(plural(r.non_manifold_vertices - open, "vertex is", "vertices are") +
                       " non-manifold (a closed fan of faces touches another fan there); first: vertex " +
                       std::to_string(first_closed) +
                       repair_hint("splits them into one copy per fan", "split_non_manifold"));
}

} // namespace iarap::mesh_checks
