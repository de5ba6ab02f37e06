#include "iarap/mesh/edge_topology.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace iarap {

EdgeTopology edge_topology(const Eigen::MatrixXi& F, int num_vertices) {
  const Eigen::Index nf = F.rows();
  // One key per face corner: the sorted vertex pair of the opposite edge, sorted to group equal edges.
  struct Half {
    std::int64_t key;
    int face;
    int corner;
  };
  std::vector<Half> halves(static_cast<size_t>(3 * nf));
  for (Eigen::Index f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      std::int64_t a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      if (a > b) std::swap(a, b);
      halves[static_cast<size_t>(3 * f + k)] = {a * num_vertices + b, static_cast<int>(f), k};
    }
  }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.key != y.key ? x.key < y.key : (x.face != y.face ? x.face < y.face : x.corner < y.corner);
  });
  size_t ne = 0;
  for (size_t i = 0; i < halves.size(); ++i)
    if (i == 0 || halves[i].key != halves[i - 1].key) ++ne;

  EdgeTopology t;
  t.E.resize(static_cast<Eigen::Index>(ne), 2);
  t.EF.setConstant(static_cast<Eigen::Index>(ne), 2, -1);
  t.EK.setConstant(static_cast<Eigen::Index>(ne), 2, -1);
  t.face_count.setZero(static_cast<Eigen::Index>(ne));
  t.FE.resize(nf, 3);
  Eigen::Index e = -1;
  for (size_t i = 0; i < halves.size(); ++i) {
    const Half& h = halves[i];
    if (i == 0 || h.key != halves[i - 1].key) {
      ++e;
      t.E(e, 0) = static_cast<int>(h.key / num_vertices);
      t.E(e, 1) = static_cast<int>(h.key % num_vertices);
    }
    const int slot = t.face_count(e)++;
    if (slot < 2) {
      t.EF(e, slot) = h.face;
      t.EK(e, slot) = h.corner;
    }
    t.FE(h.face, h.corner) = static_cast<int>(e);
  }
  return t;
}

} // namespace iarap
