// The checks of the face indices: in range, three distinct per face, every vertex used.
#include "face_index_range.h"
#include "mesh_checks.h"

namespace iarap::mesh_checks {

namespace {

bool in_range(const Eigen::MatrixXi& F, int f, int num_vertices) {
  for (int k = 0; k < 3; ++k)
    if (F(f, k) < 0 || F(f, k) >= num_vertices) return false;
  return true;
}

bool repeats_a_vertex(const Eigen::MatrixXi& F, int f) {
  return F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2);
}

} // namespace

void check_index_range(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r) {
  int first_face = -1, first_index = 0;
  for (int f = 0; f < static_cast<int>(F.rows()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k);
      if ((i < 0 || i >= num_vertices) && r.out_of_range_indices++ == 0) {
        first_face = f;
        first_index = i;
      }
    }
  if (r.out_of_range_indices > 0)
    r.errors.push_back(
        plural(r.out_of_range_indices, "face index is", "face indices are") +
        " out of range; first: " + out_of_range_face_index(first_face, first_index, num_vertices));
}

void check_repeated_vertices(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r) {
  int first = -1;
  for (int f = 0; f < static_cast<int>(F.rows()); ++f)
    if (in_range(F, f, num_vertices) && repeats_a_vertex(F, f) && r.repeated_vertex_faces++ == 0) first = f;
  if (r.repeated_vertex_faces > 0)
    r.errors.push_back(plural(r.repeated_vertex_faces, "face repeats", "faces repeat") +
                       " a vertex; first: face " + std::to_string(first) + " (" +
                       std::to_string(F(first, 0)) + ", " + std::to_string(F(first, 1)) + ", " +
                       std::to_string(F(first, 2)) + ")" +
                       repair_hint("removes them with the zero-area faces", "remove_zero_area"));
}

void check_unreferenced_vertices(const Eigen::MatrixXi& F, int num_vertices, MeshReport& r) {
  std::vector<char> used(static_cast<std::size_t>(num_vertices), 0);
  for (int f = 0; f < static_cast<int>(F.rows()); ++f)
    if (in_range(F, f, num_vertices))
      for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(F(f, k))] = 1;
  int first = -1;
  for (int v = 0; v < num_vertices; ++v)
    if (!used[static_cast<std::size_t>(v)] && r.unreferenced_vertices++ == 0) first = v;
  if (r.unreferenced_vertices > 0)
    r.warnings.push_back(plural(r.unreferenced_vertices, "vertex is", "vertices are") +
                         " used by no face; first: vertex " + std::to_string(first) +
                         repair_hint("removes them", "remove_unreferenced"));
}

CheckedFaces checked_faces(const Eigen::MatrixXi& F, int num_vertices) {
  CheckedFaces faces;
  faces.face.reserve(static_cast<std::size_t>(F.rows()));
  for (int f = 0; f < static_cast<int>(F.rows()); ++f)
    if (in_range(F, f, num_vertices) && !repeats_a_vertex(F, f)) faces.face.push_back(f);
  const int ng = static_cast<int>(faces.face.size());
  faces.G.resize(ng, 3);
  for (int g = 0; g < ng; ++g) faces.G.row(g) = F.row(faces.face[static_cast<std::size_t>(g)]);
  return faces;
}

} // namespace iarap::mesh_checks
