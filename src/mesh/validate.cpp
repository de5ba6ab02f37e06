#include "iarap/mesh/validate.h"

#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/normalize_scale.h"
#include "mesh_checks.h"

#include <cmath>

namespace iarap {

namespace mesh_checks {

std::string plural(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string repair_hint(const char* what, const char* option) {
  return std::string("; repair_mesh ") + what + " (RepairOptions::" + option + ")";
}

std::string edge_name(const EdgeTopology& t, int e) {
  return "edge (" + std::to_string(t.E(e, 0)) + ", " + std::to_string(t.E(e, 1)) + ")";
}

Eigen::VectorXi group_pairs(const std::vector<int>& a, const std::vector<int>& b, int n, int* count) {
  Eigen::MatrixXi pairs(static_cast<Eigen::Index>(a.size()), 3);
  for (std::size_t i = 0; i < a.size(); ++i) pairs.row(static_cast<Eigen::Index>(i)) << a[i], b[i], b[i];
  return vertex_components(pairs, n, count);
}

} // namespace mesh_checks

double bounding_box_diagonal(const Eigen::MatrixXd& V) {
  if (V.cols() != 3) return 0.0;
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(INFINITY),
                     hi = Eigen::RowVector3d::Constant(-INFINITY);
  bool any = false;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    if (!V.row(v).allFinite()) continue;
    lo = lo.cwiseMin(V.row(v));
    hi = hi.cwiseMax(V.row(v));
    any = true;
  }
  return any ? (hi - lo).stableNorm() : 0.0; // stableNorm: the squares of 1e200 would overflow
}

MeshReport check_mesh(const Eigen::MatrixXd& V_in, const Eigen::MatrixXi& F) {
  using namespace mesh_checks;
  // Geometry on V / s, exact for a power of two s, so that areas and cotangents neither overflow nor
  // underflow at scales like 1e300 or 1e-300; lengths are reported back in the file's units.
  const double scale = normalizing_scale(V_in);
  const Eigen::MatrixXd V = V_in / scale;
  MeshReport r;
  r.vertices = static_cast<int>(V.rows());
  r.faces = static_cast<int>(F.rows());
  if (V.cols() != 3 || F.cols() != 3) {
    r.errors.push_back("V must be #V x 3 and F #F x 3; got V " + std::to_string(V.rows()) + " x " +
                       std::to_string(V.cols()) + " and F " + std::to_string(F.rows()) + " x " +
                       std::to_string(F.cols()));
    return r;
  }
  const int nv = r.vertices;
  if (r.faces == 0) r.errors.push_back("mesh has no faces");
  // The order of the calls is the order of the messages.
  check_finite_coordinates(V, r);
  r.bbox_diagonal = bounding_box_diagonal(V); // in units of `scale` until the end
  check_index_range(F, nv, r);
  check_repeated_vertices(F, nv, r);
  check_unreferenced_vertices(F, nv, r);
  const CheckedFaces faces = checked_faces(F, nv);
  check_zero_area_faces(V, faces, r);
  const EdgeTopology t = edge_topology(faces.G, nv);
  check_edge_manifold(t, r);
  count_non_delaunay_edges(V, faces, t, r);
  check_orientation(faces, t, r);
  check_vertex_manifold(faces, t, nv, r);
  check_components(faces, t, nv, r); // the genus needs the manifold and orientation counts
  check_coincident_vertices(V, r);
  check_face_soup(faces, r);
  r.bbox_diagonal *= scale;
  return r;
}

} // namespace iarap
