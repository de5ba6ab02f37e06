#include "corner_fans.h"

#include "mesh_checks.h"

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

} // namespace iarap::mesh_checks
