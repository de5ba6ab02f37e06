#include "iarap/mesh/repair.h"

#include "face_index_range.h"
#include "face_orientation.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/validate.h"
#include "split_non_manifold.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>

namespace iarap {

namespace {

std::string count_of(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The weld target of each vertex (itself where nothing is welded).
Eigen::VectorXi weld_step(const Eigen::MatrixXd& Vn, double diagonal, const RepairOptions& options,
                          RepairResult& result) {
  const int nv = static_cast<int>(Vn.rows());
  if (!options.weld) return Eigen::VectorXi::LinSpaced(nv, 0, nv - 1);
  const Eigen::VectorXi representative = weld_representatives(Vn, options.weld_tolerance * diagonal);
  int& merged = result.counts.welded_vertices;
  for (int v = 0; v < nv; ++v) merged += representative(v) != v;
  if (merged > 0) {
    std::ostringstream tolerance;
    tolerance << options.weld_tolerance;
    result.actions.push_back("welded " + std::to_string(merged) +
                             " vertices onto coincident ones (tolerance " + tolerance.str() +
                             " x bbox diagonal)");
  }
  return representative;
}

// The rows of F that stay: not collapsed by welding, and (as the options say) not repeating a vertex, not
// of zero area, not a duplicate of an earlier face.
std::vector<int> kept_faces(const Eigen::MatrixXd& Vn, double diagonal, const Eigen::MatrixXi& F,
                            const Eigen::VectorXi& representative, const RepairOptions& options,
                            RepairCounts& counts) {
  const int nf = static_cast<int>(F.rows());
  std::vector<int> kept;
  kept.reserve(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const int a = representative(F(f, 0)), b = representative(F(f, 1)), c = representative(F(f, 2));
    const bool repeated_before = F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2);
    if (repeated_before) {
      if (options.remove_zero_area) {
        ++counts.repeated_vertex_faces;
        continue;
      }
    } else if (a == b || b == c || a == c) {
      ++counts.collapsed_faces;
      continue;
    } else if (options.remove_zero_area) {
      if (is_degenerate_face(Vn.row(a), Vn.row(b), Vn.row(c), diagonal)) {
        ++counts.zero_area_faces;
        continue;
      }
    }
    kept.push_back(f);
  }
  if (!options.remove_duplicate_faces) return kept;
  // Duplicates: equal sorted corner triples, the earliest face kept. O(#F log #F).
  std::vector<std::pair<std::array<int, 3>, int>> keys;
  keys.reserve(kept.size());
  for (int f : kept) {
    std::array<int, 3> key = {representative(F(f, 0)), representative(F(f, 1)), representative(F(f, 2))};
    std::sort(key.begin(), key.end());
    keys.emplace_back(key, f);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> duplicate(static_cast<std::size_t>(nf), 0);
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first && keys[i].first[0] != keys[i].first[1] &&
        keys[i].first[1] != keys[i].first[2]) {
      duplicate[static_cast<std::size_t>(keys[i].second)] = 1;
      ++counts.duplicate_faces;
    }
  kept.erase(
      std::remove_if(kept.begin(), kept.end(), [&](int f) { return duplicate[static_cast<std::size_t>(f)]; }),
      kept.end());
  return kept;
}

// Reverses the faces of G (#G x 3, distinct indices into n vertices) that run against the majority of
// their piece; non-orientable pieces stay as they are.
void orient_step(Eigen::MatrixXi& G, int n, RepairCounts& counts) {
  const mesh_checks::FaceOrientation o = mesh_checks::face_orientation(G, edge_topology(G, n));
  counts.non_orientable_pieces = o.non_orientable;
  std::vector<int> flipped(o.orientable.size(), 0), size(o.orientable.size(), 0);
  for (Eigen::Index g = 0; g < G.rows(); ++g) {
    ++size[static_cast<std::size_t>(o.piece[static_cast<std::size_t>(g)])];
    flipped[static_cast<std::size_t>(o.piece[static_cast<std::size_t>(g)])] +=
        o.flip[static_cast<std::size_t>(g)];
  }
  for (Eigen::Index g = 0; g < G.rows(); ++g) {
    const auto p = static_cast<std::size_t>(o.piece[static_cast<std::size_t>(g)]);
    if (!o.orientable[p]) continue;
    const bool majority_flipped = 2 * flipped[p] > size[p]; // then the seed's side is the minority
    if (static_cast<bool>(o.flip[static_cast<std::size_t>(g)]) != majority_flipped) {
      std::swap(G(g, 1), G(g, 2));
      ++counts.flipped_faces;
    }
  }
}

void describe_face_and_topology_changes(const RepairCounts& c, RepairResult& result) {
  auto& a = result.actions;
  if (c.collapsed_faces > 0)
    a.push_back("removed " + std::to_string(c.collapsed_faces) + " faces that welding collapsed");
  if (c.repeated_vertex_faces > 0)
    a.push_back("removed " + count_of(c.repeated_vertex_faces, "face that repeats", "faces that repeat") +
                " a vertex (zero area)");
  if (c.zero_area_faces > 0)
    a.push_back("removed " + std::to_string(c.zero_area_faces) +
                " zero-area faces (area <= 1e-12 x bbox diagonal^2)");
  if (c.duplicate_faces > 0)
    a.push_back("removed " + count_of(c.duplicate_faces, "duplicate face", "duplicate faces") +
                " (the same three vertices as an earlier face)");
  if (c.split_edges > 0)
    a.push_back("separated the faces of " +
                count_of(c.split_edges, "non-manifold edge", "non-manifold edges") + " into manifold sheets");
  if (c.split_vertices > 0)
    a.push_back("split " + count_of(c.split_vertices, "non-manifold vertex", "non-manifold vertices") +
                " into one copy per fan of faces (" + count_of(c.vertex_copies, "copy", "copies") +
                " added)");
  if (c.flipped_faces > 0)
    a.push_back("reversed " + count_of(c.flipped_faces, "face", "faces") +
                " to orient each piece consistently (as most of its faces were)");
  if (c.non_orientable_pieces > 0)
    a.push_back("left " + count_of(c.non_orientable_pieces, "non-orientable piece", "non-orientable pieces") +
                " as they are: no choice of face orientations is consistent (a Moebius strip)");
}

} // namespace

RepairResult repair_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RepairOptions& options) {
  require_triangle_mesh(V, F, "repair_mesh");
  const int nv = static_cast<int>(V.rows());
  RepairResult result;
  // Tolerances and areas on V / s (exact for a power of two s), so that they hold at any scale.
  const Eigen::MatrixXd Vn = V / normalizing_scale(V);
  const double diagonal = bounding_box_diagonal(Vn);
  const Eigen::VectorXi representative = weld_step(Vn, diagonal, options, result);
  const std::vector<int> kept = kept_faces(Vn, diagonal, F, representative, options, result.counts);

  // Faces of three distinct vertices (all, unless faces repeating a vertex are kept) are split and
  // oriented; G holds them on the weld targets, copies numbered from nv on.
  std::vector<int> proper;
  for (int f : kept) {
    const int a = representative(F(f, 0)), b = representative(F(f, 1)), c = representative(F(f, 2));
    if (a != b && b != c && a != c) proper.push_back(f);
  }
  Eigen::MatrixXi G(static_cast<Eigen::Index>(proper.size()), 3);
  for (std::size_t i = 0; i < proper.size(); ++i)
    for (int k = 0; k < 3; ++k) G(static_cast<Eigen::Index>(i), k) = representative(F(proper[i], k));
  std::vector<int> copy_of;
  if (options.split_non_manifold) {
    mesh_checks::ManifoldSplit split = mesh_checks::split_non_manifold(Vn, G, options.split_open_fans);
    G = std::move(split.F);
    copy_of = std::move(split.copy_of);
    result.counts.split_edges = split.split_edges;
    result.counts.split_vertices = split.split_vertices;
    result.counts.vertex_copies = static_cast<int>(copy_of.size());
  }
  const int n = nv + static_cast<int>(copy_of.size());
  if (options.orient) orient_step(G, n, result.counts);
  describe_face_and_topology_changes(result.counts, result);

  // Renumbering: the weld targets that stay, in order, then the copies.
  Eigen::MatrixXi faces(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0, j = 0; i < kept.size(); ++i) {
    const bool is_proper = j < proper.size() && proper[j] == kept[i];
    for (int k = 0; k < 3; ++k)
      faces(static_cast<Eigen::Index>(i), k) =
          is_proper ? G(static_cast<Eigen::Index>(j), k) : representative(F(kept[i], k));
    j += is_proper;
  }
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  for (Eigen::Index i = 0; i < faces.size(); ++i) used[static_cast<std::size_t>(faces.data()[i])] = 1;
  std::vector<int> new_index(static_cast<std::size_t>(n), -1);
  int count = 0;
  for (int v = 0; v < n; ++v) {
    if (v < nv && representative(v) != v) continue;
    if (options.remove_unreferenced && !used[static_cast<std::size_t>(v)]) {
      ++result.counts.unreferenced_vertices;
      continue;
    }
    new_index[static_cast<std::size_t>(v)] = count++;
  }
  if (result.counts.unreferenced_vertices > 0)
    result.actions.push_back("removed " + std::to_string(result.counts.unreferenced_vertices) +
                             " unreferenced vertices");

  result.old_to_new.resize(nv);
  for (int v = 0; v < nv; ++v) result.old_to_new(v) = new_index[static_cast<std::size_t>(representative(v))];
  result.V.resize(count, 3);
  result.new_to_old.resize(count);
  for (int v = 0; v < n; ++v) {
    const int to = new_index[static_cast<std::size_t>(v)];
    if (to < 0) continue;
    const int from = v < nv ? v : copy_of[static_cast<std::size_t>(v - nv)];
    result.new_to_old(to) = from;
    result.V.row(to) = V.row(from);
  }
  result.F.resize(faces.rows(), 3);
  for (Eigen::Index i = 0; i < faces.size(); ++i)
    result.F.data()[i] = new_index[static_cast<std::size_t>(faces.data()[i])];
  return result;
}

} // namespace iarap
