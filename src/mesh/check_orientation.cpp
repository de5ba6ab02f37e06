#include "face_orientation.h"
#include "mesh_checks.h"

namespace iarap::mesh_checks {

void check_orientation(const CheckedFaces& faces, const EdgeTopology& t, MeshReport& r) {
  const Eigen::MatrixXi& G = faces.G;
  int first_edge = -1;
  for (int e = 0; e < static_cast<int>(t.E.rows()); ++e) {
    if (t.face_count(e) != 2) continue;
    // Each face runs along the edge from corner k+1 to corner k+2; consistent neighbours run opposite ways.
    const int f0 = t.EF(e, 0), f1 = t.EF(e, 1), k0 = t.EK(e, 0), k1 = t.EK(e, 1);
    if (G(f0, (k0 + 1) % 3) == G(f1, (k1 + 1) % 3) && r.inconsistently_oriented_edges++ == 0) first_edge = e;
  }
  const FaceOrientation orientation = face_orientation(G, t);
  r.non_orientable_components = orientation.non_orientable;
  const int first_face = orientation.first_conflict;
  if (r.inconsistently_oriented_edges == 0) return;
  ++r.oriented_manifold_errors; // one of the two messages below
  const auto face = [&](int g) { return std::to_string(faces.face[static_cast<std::size_t>(g)]); };
  const std::string where = "; first: " + edge_name(t, first_edge) + " between faces " +
                            face(t.EF(first_edge, 0)) + " and " + face(t.EF(first_edge, 1));
  const std::string edges = plural(r.inconsistently_oriented_edges, "edge joins", "edges join");
  if (r.non_orientable_components > 0)
    r.errors.push_back(
        "the surface is non-orientable (" +
        plural(r.non_orientable_components, "component has", "components have") +
        " no consistent orientation, like a Moebius strip or a Klein bottle; first: the "
        "component of face " +
        face(first_face) +
        "): no choice of face orientations fixes it (ARAP deforms it as it is, on its tufted cover); " +
        edges + " faces oriented in the same direction" + where);
  else
    r.errors.push_back(edges + " inconsistently oriented faces" + where + "; the surface is orientable" +
                       repair_hint("reverses the faces that disagree with most of their piece", "orient"));
}

} // namespace iarap::mesh_checks
