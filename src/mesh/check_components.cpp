#include "iarap/mesh/connected_components.h"
#include "mesh_checks.h"

#include <cstdint>

namespace iarap::mesh_checks {

void check_components(const CheckedFaces& faces, const EdgeTopology& t, int num_vertices, MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  const int ng = static_cast<int>(G.rows()), ne = static_cast<int>(t.E.rows()), nv = num_vertices;
  int raw_components = 0;
  const Eigen::VectorXi component = vertex_components(G, nv, &raw_components);
  std::vector<char> in_mesh(static_cast<std::size_t>(nv), 0);
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) in_mesh[static_cast<std::size_t>(G(g, k))] = 1;
  std::vector<int> dense(static_cast<std::size_t>(raw_components), -1); // component id among face components
  for (int v = 0; v < nv; ++v)
    if (in_mesh[static_cast<std::size_t>(v)] && dense[static_cast<std::size_t>(component(v))] < 0)
      dense[static_cast<std::size_t>(component(v))] = r.components++;
  const auto comp = [&](int v) { return dense[static_cast<std::size_t>(component(v))]; };

  // Boundary loops: the boundary edges' connected groups, counted per component.
  std::vector<int> bound_a, bound_b;
  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (int e = 0; e < ne; ++e)
    if (t.face_count(e) == 1) {
      bound_a.push_back(t.E(e, 0));
      bound_b.push_back(t.E(e, 1));
      on_boundary[static_cast<std::size_t>(t.E(e, 0))] = on_boundary[static_cast<std::size_t>(t.E(e, 1))] = 1;
    }
  int raw_loops = 0;
  const Eigen::VectorXi loop = group_pairs(bound_a, bound_b, nv, &raw_loops);
  std::vector<char> loop_seen(static_cast<std::size_t>(raw_loops), 0);
  std::vector<std::int64_t> loops_in(static_cast<std::size_t>(r.components), 0),
      chi(static_cast<std::size_t>(r.components), 0);
  for (int v = 0; v < nv; ++v) {
    if (!in_mesh[static_cast<std::size_t>(v)]) continue;
    ++chi[static_cast<std::size_t>(comp(v))];
    if (on_boundary[static_cast<std::size_t>(v)] && !loop_seen[static_cast<std::size_t>(loop(v))]) {
      loop_seen[static_cast<std::size_t>(loop(v))] = 1;
      ++loops_in[static_cast<std::size_t>(comp(v))];
      ++r.boundary_loops;
    }
  }

  // Genus: chi = V - E + F per component, genus = (2 - chi - b) / 2. Only for an orientable manifold: a
  // non-orientable surface of even 2 - chi - b (the Klein bottle: 0 - 0 + 2) would otherwise pass for an
  // orientable one of genus (2 - chi - b) / 2.
  for (int e = 0; e < ne; ++e) --chi[static_cast<std::size_t>(comp(t.E(e, 0)))];
  for (int g = 0; g < ng; ++g) ++chi[static_cast<std::size_t>(comp(G(g, 0)))];
  if (r.non_manifold_edges != 0 || r.non_manifold_vertices != 0 || r.non_orientable_components != 0) return;
  std::int64_t genus = 0;
  bool valid = true;
  for (int c = 0; c < r.components; ++c) {
    const std::int64_t twice = 2 - chi[static_cast<std::size_t>(c)] - loops_in[static_cast<std::size_t>(c)];
    if (twice % 2 != 0 || twice < 0) valid = false;
    genus += twice / 2;
  }
  if (valid) r.genus = static_cast<int>(genus);
}

void check_face_soup(const CheckedFaces& faces, MeshReport& r) {
  const int ng = static_cast<int>(faces.G.rows());
  if (ng > 1 && r.components == ng)
    r.warnings.push_back("the mesh falls apart into one component per face (" + std::to_string(ng) +
                         "): faces share no vertices, as in an unwelded triangle soup (STL)" +
                         repair_hint("welds it", "weld"));
}

} // namespace iarap::mesh_checks
