#include "face_orientation.h"

namespace iarap::mesh_checks {

FaceOrientation face_orientation(const Eigen::MatrixXi& G, const EdgeTopology& t) {
  const int ng = static_cast<int>(G.rows());
  FaceOrientation o;
  std::vector<signed char> flip(static_cast<std::size_t>(ng), -1);
  o.piece.assign(static_cast<std::size_t>(ng), -1);
  std::vector<int> stack;
  for (int seed = 0; seed < ng; ++seed) {
    if (flip[static_cast<std::size_t>(seed)] >= 0) continue;
    const int piece = static_cast<int>(o.orientable.size());
    flip[static_cast<std::size_t>(seed)] = 0;
    o.piece[static_cast<std::size_t>(seed)] = piece;
    stack.assign(1, seed);
    bool orientable = true;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int e = t.FE(g, k);
        if (t.face_count(e) != 2) continue;
        // Each face runs along the edge from corner k+1 to corner k+2; consistent neighbours run opposite
        // ways, so across an edge whose faces run the same way the bit changes.
        const int side = t.EF(e, 0) == g ? 0 : 1;
        const int h = t.EF(e, 1 - side), kh = t.EK(e, 1 - side);
        const bool same_direction = G(g, (k + 1) % 3) == G(h, (kh + 1) % 3);
        const signed char want = static_cast<signed char>(flip[static_cast<std::size_t>(g)] ^ same_direction);
        signed char& have = flip[static_cast<std::size_t>(h)];
        if (have < 0) {
          have = want;
          o.piece[static_cast<std::size_t>(h)] = piece;
          stack.push_back(h);
        } else if (have != want && orientable) {
          orientable = false;
          if (o.non_orientable == 0) o.first_conflict = h;
        }
      }
    }
    o.orientable.push_back(orientable);
    o.non_orientable += !orientable;
  }
  o.flip.assign(flip.begin(), flip.end());
  return o;
}

} // namespace iarap::mesh_checks
