// The checks of the vertex coordinates: finite, and no two vertices at one position.
#include "iarap/mesh/weld_representatives.h"
#include "mesh_checks.h"

namespace iarap::mesh_checks {

namespace {
constexpr double coincident_factor = 1e-12; // times bbox_diagonal (validate.h)
} // namespace

void check_finite_coordinates(const Eigen::MatrixXd& V, MeshReport& r) {
  int first = -1;
  for (int v = 0; v < static_cast<int>(V.rows()); ++v)
    if (!V.row(v).allFinite() && r.non_finite_coordinates++ == 0) first = v;
  if (r.non_finite_coordinates > 0)
    r.errors.push_back(plural(r.non_finite_coordinates, "vertex has", "vertices have") +
                       " a NaN or Inf coordinate; first: vertex " + std::to_string(first));
}

void check_coincident_vertices(const Eigen::MatrixXd& V, MeshReport& r) {
  const Eigen::VectorXi representative = weld_representatives(V, coincident_factor * r.bbox_diagonal);
  int first = -1;
  for (int v = 0; v < static_cast<int>(V.rows()); ++v)
    if (representative(v) != v && r.coincident_vertices++ == 0) first = v;
  if (r.coincident_vertices > 0)
    r.warnings.push_back(plural(r.coincident_vertices, "vertex coincides", "vertices coincide") +
                         " with an earlier vertex (within 1e-12 x bbox diagonal); first: vertex " +
                         std::to_string(first) + " at the position of vertex " +
                         std::to_string(representative(first)) + repair_hint("welds them", "weld"));
}

} // namespace iarap::mesh_checks
