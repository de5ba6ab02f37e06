#include "split_non_manifold.h"

#include "corner_fans.h"
#include "iarap/mesh/edge_topology.h"
#include "mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace iarap::mesh_checks {

namespace {

// Unit direction from edge (a, b) towards its third vertex c, perpendicular to the edge; zero where that
// is degenerate or not finite, so that the pairing never compares a NaN.
Eigen::RowVector3d away_from_edge(const Eigen::MatrixXd& V, int a, int b, int c) {
  const Eigen::RowVector3d u = V.row(b) - V.row(a), w = V.row(c) - V.row(a);
  const double uu = u.squaredNorm();
  const Eigen::RowVector3d d = uu > 0 ? Eigen::RowVector3d(w - (w.dot(u) / uu) * u) : w;
  const double length = d.norm();
  if (!(length > 0) || !std::isfinite(length)) return Eigen::RowVector3d::Zero();
  return d / length;
}

// The sheet of each edge slot 3 g + k (corner_fans.h): edge t.FE(g, k) where the edge has one or two
// faces; at a non-manifold edge each pair and each face left over is a sheet of its own, numbered from #E
// on. flattest marks the slots of each non-manifold edge's first (flattest) pair, ends the vertices of
// the non-manifold edges.
struct Sheets {
  std::vector<int> sheet;
  int count = 0;
  std::vector<char> flattest, ends;
  int non_manifold_edges = 0;
};

// Pairs the faces of one non-manifold edge (their slots) flattest first into new sheets of s.
void pair_faces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& G, const Eigen::VectorXi& piece, int a,
                int b, const std::vector<int>& slots, Sheets& s) {
  const int m = static_cast<int>(slots.size());
  std::vector<Eigen::RowVector3d> away;
  for (int slot : slots) away.push_back(away_from_edge(V, a, b, G(slot / 3, slot % 3)));
  // (apart, cosine, p, q): faces of one piece first, then the most nearly opposite.
  std::vector<std::tuple<bool, double, int, int>> pairs;
  const auto piece_of = [&](int i) { return piece(slots[static_cast<std::size_t>(i)] / 3); };
  if (m <= max_paired_faces)
    for (int p = 0; p < m; ++p)
      for (int q = p + 1; q < m; ++q)
        pairs.emplace_back(piece_of(p) != piece_of(q),
                           away[static_cast<std::size_t>(p)].dot(away[static_cast<std::size_t>(q)]), p, q);
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> taken(static_cast<std::size_t>(m), 0);
  bool first = true;
  for (const auto& [apart, cosine, p, q] : pairs) {
    if (taken[static_cast<std::size_t>(p)] || taken[static_cast<std::size_t>(q)]) continue;
    taken[static_cast<std::size_t>(p)] = taken[static_cast<std::size_t>(q)] = 1;
    for (int i : {p, q}) {
      const auto slot = static_cast<std::size_t>(slots[static_cast<std::size_t>(i)]);
      s.sheet[slot] = s.count;
      s.flattest[slot] = first;
    }
    ++s.count;
    first = false;
  }
  for (int p = 0; p < m; ++p)
    if (!taken[static_cast<std::size_t>(p)])
      s.sheet[static_cast<std::size_t>(slots[static_cast<std::size_t>(p)])] = s.count++;
}

Sheets edge_sheets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& G, const EdgeTopology& t, int nv) {
  const int ng = static_cast<int>(G.rows());
  Sheets s;
  s.sheet.resize(static_cast<std::size_t>(3 * ng));
  s.flattest.assign(static_cast<std::size_t>(3 * ng), 0);
  s.ends.assign(static_cast<std::size_t>(nv), 0);
  s.count = static_cast<int>(t.E.rows());
  std::vector<std::pair<int, int>> crowded; // (edge, slot) of the non-manifold edges
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) {
      const int e = t.FE(g, k);
      s.sheet[static_cast<std::size_t>(3 * g + k)] = e;
      if (t.face_count(e) > 2) crowded.emplace_back(e, 3 * g + k);
    }
  std::sort(crowded.begin(), crowded.end());
  if (crowded.empty()) return s;
  // Pieces: faces joined across the edges of two faces, so that a pair from one piece (the surface a fin
  // or a stray face was stuck on) wins over a flatter pair across pieces.
  std::vector<int> across_a, across_b;
  for (Eigen::Index e = 0; e < t.E.rows(); ++e)
    if (t.face_count(e) == 2) {
      across_a.push_back(t.EF(e, 0));
      across_b.push_back(t.EF(e, 1));
    }
  const Eigen::VectorXi piece = group_pairs(across_a, across_b, ng, nullptr);
  std::vector<int> slots;
  for (std::size_t i = 0, j = 0; i < crowded.size(); i = j) {
    const int e = crowded[i].first;
    slots.clear();
    for (j = i; j < crowded.size() && crowded[j].first == e; ++j) slots.push_back(crowded[j].second);
    ++s.non_manifold_edges;
    s.ends[static_cast<std::size_t>(t.E(e, 0))] = s.ends[static_cast<std::size_t>(t.E(e, 1))] = 1;
    pair_faces(V, G, piece, t.E(e, 0), t.E(e, 1), slots, s);
  }
  return s;
}

// A new vertex copying v (itself an input vertex or a copy).
int new_copy(ManifoldSplit& out, int num_input, int v) {
  const int index = num_input + static_cast<int>(out.copy_of.size());
  out.copy_of.push_back(v < num_input ? v : out.copy_of[static_cast<std::size_t>(v - num_input)]);
  return index;
}

// Gives each fan that must be separated (see the header; all fans at the vertices `separate`) a vertex of
// its own, in place on out.F.
void split_fans(ManifoldSplit& out, const EdgeTopology& t, const Sheets& s, bool split_open_fans,
                int num_input) {
  Eigen::MatrixXi& G = out.F;
  const int ng = static_cast<int>(G.rows()), n = num_input + static_cast<int>(out.copy_of.size());
  const Eigen::VectorXi fan = corner_fans(G, t, s.sheet, s.count);
  const int fans = ng > 0 ? fan.maxCoeff() + 1 : 0;
  std::vector<int> faces_of_sheet(static_cast<std::size_t>(s.count), 0);
  for (int slot : s.sheet) ++faces_of_sheet[static_cast<std::size_t>(slot)];
  // A fan is open where one of its edges at the vertex is a sheet of one face.
  std::vector<char> open(static_cast<std::size_t>(fans), 0);
  std::vector<int> vertex_of(static_cast<std::size_t>(fans), -1), fans_at(static_cast<std::size_t>(n), 0);
  for (int c = 0; c < 3 * ng; ++c) {
    const int g = c / 3, k = c % 3;
    const auto f = static_cast<std::size_t>(fan(c));
    for (int side : {1, 2})
      if (faces_of_sheet[static_cast<std::size_t>(
              s.sheet[static_cast<std::size_t>(3 * g + (k + side) % 3)])] == 1)
        open[f] = 1;
    if (vertex_of[f] < 0) ++fans_at[static_cast<std::size_t>(G(g, k))];
    vertex_of[f] = G(g, k);
  }
  std::vector<char> closed_at(static_cast<std::size_t>(n), 0);
  for (int f = 0; f < fans; ++f)
    if (!open[static_cast<std::size_t>(f)])
      closed_at[static_cast<std::size_t>(vertex_of[static_cast<std::size_t>(f)])] = 1;
  std::vector<int> target(static_cast<std::size_t>(fans), -1), open_target(static_cast<std::size_t>(n), -1);
  std::vector<char> original_taken(static_cast<std::size_t>(n), 0);
  for (int c = 0; c < 3 * ng; ++c) {
    const auto f = static_cast<std::size_t>(fan(c));
    if (target[f] >= 0) continue;
    const int v = vertex_of[f];
    const auto vi = static_cast<std::size_t>(v);
    const bool every_fan = split_open_fans || (vi < s.ends.size() && s.ends[vi]);
    const bool split = fans_at[vi] > 1 && (closed_at[vi] || every_fan);
    const bool together = split && open[f] && !every_fan; // the open fans of v share one vertex
    if (!split) {
      target[f] = v;
    } else if (together && open_target[vi] >= 0) {
      target[f] = open_target[vi];
    } else {
      target[f] = original_taken[vi] ? new_copy(out, num_input, v) : v;
      original_taken[vi] = 1;
      if (together) open_target[vi] = target[f];
    }
  }
  for (int c = 0; c < 3 * ng; ++c) G(c / 3, c % 3) = target[static_cast<std::size_t>(fan(c))];
}

// Faces whose fans meet around both ends of a separated edge through other faces still share the edge
// after split_fans: all but the flattest pair get fresh vertices at its ends. Returns whether any did.
bool detach_extra_faces(const Eigen::MatrixXd& V, ManifoldSplit& out, const EdgeTopology& t, int num_input) {
  Eigen::MatrixXd positions(num_input + static_cast<Eigen::Index>(out.copy_of.size()), 3);
  positions.topRows(num_input) = V;
  for (std::size_t i = 0; i < out.copy_of.size(); ++i)
    positions.row(num_input + static_cast<Eigen::Index>(i)) = V.row(out.copy_of[i]);
  const Sheets s = edge_sheets(positions, out.F, t, static_cast<int>(positions.rows()));
  if (s.non_manifold_edges == 0) return false;
  std::vector<char> detached(static_cast<std::size_t>(3 * out.F.rows()), 0); // per corner
  for (Eigen::Index g = 0; g < out.F.rows(); ++g)
    for (int k = 0; k < 3; ++k) {
      const auto slot = static_cast<std::size_t>(3 * g + k);
      if (t.face_count(t.FE(g, k)) <= 2 || s.flattest[slot]) continue;
      for (int side : {1, 2}) {
        const int corner = (k + side) % 3;
        char& done = detached[static_cast<std::size_t>(3 * g + corner)];
        if (!done) out.F(g, corner) = new_copy(out, num_input, out.F(g, corner));
        done = 1;
      }
    }
  return true;
}

Sheets plain_sheets(const EdgeTopology& t, Eigen::Index faces) {
  Sheets s;
  s.count = static_cast<int>(t.E.rows());
  s.sheet.resize(static_cast<std::size_t>(3 * faces));
  for (Eigen::Index g = 0; g < faces; ++g)
    for (int k = 0; k < 3; ++k) s.sheet[static_cast<std::size_t>(3 * g + k)] = t.FE(g, k);
  return s;
}

} // namespace

ManifoldSplit split_non_manifold(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, bool split_open_fans) {
  const int nv = static_cast<int>(V.rows());
  ManifoldSplit out;
  out.F = F;
  EdgeTopology t = edge_topology(out.F, nv);
  const Sheets sheets = edge_sheets(V, out.F, t, nv);
  out.split_edges = sheets.non_manifold_edges;
  split_fans(out, t, sheets, split_open_fans, nv);
  const auto vertex_count = [&] { return nv + static_cast<int>(out.copy_of.size()); };
  if (out.split_edges > 0) {
    t = edge_topology(out.F, vertex_count());
    if (detach_extra_faces(V, out, t, nv)) {
      t = edge_topology(out.F, vertex_count());
      split_fans(out, t, plain_sheets(t, out.F.rows()), split_open_fans, nv);
    }
  }
  std::vector<int> split = out.copy_of;
  std::sort(split.begin(), split.end());
  out.split_vertices = static_cast<int>(std::unique(split.begin(), split.end()) - split.begin());
  return out;
}

} // namespace iarap::mesh_checks
