#include "iarap/mesh/cotan.h"
#include "mesh_checks.h"

namespace iarap::mesh_checks {

namespace {
// Cotangents are dimensionless; exact right angles of regular grids compute to +-1e-16, not a real violation.
constexpr double delaunay_tolerance = 1e-12;
} // namespace

void count_non_delaunay_edges(const Eigen::MatrixXd& V, const CheckedFaces& faces, const EdgeTopology& t,
                              MeshReport& r) {
  const Eigen::MatrixXd C = face_cotangents(V, faces.G);
  for (int e = 0; e < static_cast<int>(t.E.rows()); ++e)
    if (t.face_count(e) == 2 && C(t.EF(e, 0), t.EK(e, 0)) + C(t.EF(e, 1), t.EK(e, 1)) < -delaunay_tolerance)
      ++r.non_delaunay_edges;
}

} // namespace iarap::mesh_checks
