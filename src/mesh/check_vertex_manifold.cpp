#include "corner_fans.h"
#include "mesh_checks.h"

namespace iarap::mesh_checks {

void check_vertex_manifold(const CheckedFaces& faces, const EdgeTopology& t, int num_vertices,
                           MeshReport& r) {
  const PinchedVertices pinched = pinched_vertices(faces.G, t, num_vertices);
  const int open = static_cast<int>(pinched.open.size());
  r.non_manifold_vertices = open + static_cast<int>(pinched.closed.size());
  // A pinched vertex whose fans are all open is where separate sheets touch, common in scans: ARAP keeps one
  // rotation cell there and the intrinsic triangulation gives each fan its own angle range, so it is only a
  // warning. A closed fan touching another is an error.
  const int first_open = open > 0 ? pinched.open.front() : -1;
  const int first_closed = pinched.closed.empty() ? -1 : pinched.closed.front();
  if (open > 0)
    r.warnings.push_back(plural(open, "vertex joins", "vertices join") +
                         " several open fans of faces (sheets touching at a point; handled as one rotation "
                         "cell); first: vertex " +
                         std::to_string(first_open));
  if (r.non_manifold_vertices == open) return;
  ++r.oriented_manifold_errors;
  r.errors.push_back(plural(r.non_manifold_vertices - open, "vertex is", "vertices are") +
                     " non-manifold (a closed fan of faces touches another fan there); first: vertex " +
                     std::to_string(first_closed) +
                     repair_hint("splits them into one copy per fan", "split_non_manifold"));
}

} // namespace iarap::mesh_checks
