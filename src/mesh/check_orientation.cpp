#include "mesh_checks.h"

namespace iarap::mesh_checks {

namespace {

// Per face component (faces joined through manifold edges): whether its faces can be oriented
// consistently, found by propagating a flip bit face to face: across an edge whose two faces run the same
// way the bit changes, else it stays; a face reached with both bits lies on a non-orientable surface
// (Moebius strip, Klein bottle). Returns the number of such components; first_bad gets one of their faces.
int non_orientable_components(const Eigen::MatrixXi& G, const EdgeTopology& t, int* first_bad) {
  const int ng = static_cast<int>(G.rows());
  std::vector<signed char> flip(static_cast<std::size_t>(ng), -1);
  std::vector<int> stack;
  int bad = 0;
  for (int seed = 0; seed < ng; ++seed) {
    if (flip[static_cast<std::size_t>(seed)] >= 0) continue;
    flip[static_cast<std::size_t>(seed)] = 0;
    stack.assign(1, seed);
    bool orientable = true;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int e = t.FE(g, k);
        if (t.face_count(e) != 2) continue;
        const int side = t.EF(e, 0) == g ? 0 : 1;
        const int h = t.EF(e, 1 - side), kh = t.EK(e, 1 - side);
        const bool same_direction = G(g, (k + 1) % 3) == G(h, (kh + 1) % 3);
        const signed char want = static_cast<signed char>(flip[static_cast<std::size_t>(g)] ^ same_direction);
        signed char& have = flip[static_cast<std::size_t>(h)];
        if (have < 0) {
          have = want;
          stack.push_back(h);
        } else if (have != want && orientable) {
          orientable = false;
          if (bad == 0 && first_bad) *first_bad = h;
        }
      }
    }
    bad += !orientable;
  }
  return bad;
}

} // namespace

void check_orientation(const CheckedFaces& faces, const EdgeTopology& t, MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  int first_edge = -1;
  for (int e = 0; e < static_cast<int>(t.E.rows()); ++e) {
    if (t.face_count(e) != 2) continue;
    // Each face runs along the edge from corner k+1 to corner k+2; consistent neighbours run opposite ways.
    const int f0 = t.EF(e, 0), f1 = t.EF(e, 1), k0 = t.EK(e, 0), k1 = t.EK(e, 1);
    if (G(f0, (k0 + 1) % 3) == G(f1, (k1 + 1) % 3) && r.inconsistently_oriented_edges++ == 0) first_edge = e;
  }
  int first_face = -1;
  r.non_orientable_components = non_orientable_components(G, t, &first_face);
  if (r.inconsistently_oriented_edges == 0) return;
  const auto face = [&](int g) { return std::to_string(faces.face[static_cast<std::size_t>(g)]); };
  const std::string where = "; first: " + edge_name(t, first_edge) + " between faces " +
                            face(t.EF(first_edge, 0)) + " and " + face(t.EF(first_edge, 1));
  const std::string edges = plural(r.inconsistently_oriented_edges, "edge joins", "edges join");
  if (r.non_orientable_components > 0)
    r.errors.push_back("the surface is non-orientable (" +
                       plural(r.non_orientable_components, "component has", "components have") +
                       " no consistent orientation, like a Moebius strip or a Klein bottle; first: the "
                       "component of face " +
                       face(first_face) + "): no choice of face orientations fixes it, and ARAP needs one; " +
                       edges + " faces oriented in the same direction" + where);
  else
    r.errors.push_back(edges + " inconsistently oriented faces" + where +
                       "; the surface is orientable: reverse the faces of one side (re-export with "
                       "consistent normals)");
}

} // namespace iarap::mesh_checks
