#include "mesh_checks.h"

namespace iarap::mesh_checks {

void check_zero_area_faces(const Eigen::MatrixXd& V, const CheckedFaces& faces, MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  int first = -1;
  for (int g = 0; g < static_cast<int>(G.rows()); ++g)
    if (is_degenerate_face(V.row(G(g, 0)), V.row(G(g, 1)), V.row(G(g, 2)), r.bbox_diagonal) &&
        r.zero_area_faces++ == 0)
      first = faces.face[static_cast<std::size_t>(g)];
  if (r.zero_area_faces > 0)
    r.warnings.push_back(plural(r.zero_area_faces, "face has", "faces have") +
                         " zero area (<= 1e-12 x bbox diagonal^2, or edge lengths that make no triangle); "
                         "first: face " +
                         std::to_string(first) + repair_hint("drops them", "remove_zero_area"));
}

} // namespace iarap::mesh_checks
