#include "mesh_checks.h"

#include <Eigen/Geometry>

namespace iarap::mesh_checks {

namespace {
constexpr double zero_area_factor = 1e-12; // times bbox_diagonal^2 (validate.h)
} // namespace

void check_zero_area_faces(const Eigen::MatrixXd& V, const CheckedFaces& faces, MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  const double min_area = zero_area_factor * r.bbox_diagonal * r.bbox_diagonal;
  int first = -1;
  for (int g = 0; g < static_cast<int>(G.rows()); ++g) {
    const Eigen::RowVector3d a = V.row(G(g, 0)), b = V.row(G(g, 1)), c = V.row(G(g, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (area <= min_area && r.zero_area_faces++ == 0) first = faces.face[static_cast<std::size_t>(g)];
  }
  if (r.zero_area_faces > 0)
    r.warnings.push_back(plural(r.zero_area_faces, "face has", "faces have") +
                         " zero area (<= 1e-12 x bbox diagonal^2); first: face " + std::to_string(first) +
                         repair_hint("drops them", "remove_zero_area"));
}

} // namespace iarap::mesh_checks
