#include "corner_fans.h"

#include "mesh_checks.h"

#include <algorithm>
#include <utility>

namespace iarap::mesh_checks {

Eigen::VectorXi corner_fans(const Eigen::MatrixXi& G, const EdgeTopology& t, const std::vector<int>& sheet,
                            int sheet_count) {
  const int ng = static_cast<int>(G.rows());
  std::vector<int> join_a, join_b;
  join_a.reserve(static_cast<std::size_t>(6 * ng));
  join_b.reserve(static_cast<std::size_t>(6 * ng));
  // Per sheet end (2 s + 0 at E(e, 0), 2 s + 1 at E(e, 1)): the first corner seen there.
  std::vector<int> first_corner(static_cast<std::size_t>(2 * sheet_count), -1);
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) {
      const int e = t.FE(g, k), s = sheet[static_cast<std::size_t>(3 * g + k)];
      for (int end = 0; end < 2; ++end) {
        const int corner_k = G(g, (k + 1) % 3) == t.E(e, end) ? (k + 1) % 3 : (k + 2) % 3;
        const int corner = 3 * g + corner_k;
        int& seen = first_corner[static_cast<std::size_t>(2 * s + end)];
        if (seen < 0) {
          seen = corner;
        } else {
          join_a.push_back(seen);
          join_b.push_back(corner);
        }
      }
    }
  return group_pairs(join_a, join_b, 3 * ng, nullptr);
}

Eigen::VectorXi corner_fans(const Eigen::MatrixXi& G, const EdgeTopology& t) {
  std::vector<int> sheet(static_cast<std::size_t>(3 * G.rows()));
  for (Eigen::Index g = 0; g < G.rows(); ++g)
    for (int k = 0; k < 3; ++k) sheet[static_cast<std::size_t>(3 * g + k)] = t.FE(g, k);
  return corner_fans(G, t, sheet, static_cast<int>(t.E.rows()));
}

PinchedVertices pinched_vertices(const Eigen::MatrixXi& G, const EdgeTopology& t, int num_vertices) {
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
  PinchedVertices out;
  if (std::find(pinched.begin(), pinched.end(), 1) == pinched.end()) return out;
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
  for (int v = 0; v < nv; ++v) {
    if (!pinched[static_cast<std::size_t>(v)]) continue;
    // Each open fan ends on two boundary edges at v.
    const bool all_open =
        boundary_at[static_cast<std::size_t>(v)] == 2 * fan_count[static_cast<std::size_t>(v)];
    (all_open ? out.open : out.closed).push_back(v);
  }
  return out;
}

} // namespace iarap::mesh_checks
