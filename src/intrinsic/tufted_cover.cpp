#include "tufted_cover.h"

#include "signpost_triangulation.h"

#include "../mesh/corner_fans.h"
#include "../mesh/mesh_checks.h"
#include "iarap/core/threads.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace iarap::detail {

namespace {

// Cover halfedges of input face f along its edge opposite corner k, which runs F(f, k+1) -> F(f, k+2) in
// the front copy (a, b, c) and back in the back copy (a, c, b), whose corners are input corners 0, 2, 1.
int front_halfedge(int f, int k) {
  return 6 * f + (k + 1) % 3;
}
int back_halfedge(int f, int k) {
  constexpr int back_corner[3] = {0, 2, 1};
  return 6 * f + 3 + back_corner[(k + 2) % 3];
}

// The input faces of each edge as (face, corner opposite the edge), CSR by edge: all of them, where
// EdgeTopology keeps two.
void sides_by_edge(const EdgeTopology& topology, int num_faces, std::vector<int>& start,
                   std::vector<int>& side) {
  const int ne = static_cast<int>(topology.E.rows());
  start.assign(static_cast<size_t>(ne) + 1, 0);
  for (int f = 0; f < num_faces; ++f)
    for (int k = 0; k < 3; ++k) ++start[static_cast<size_t>(topology.FE(f, k)) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  side.resize(static_cast<size_t>(3 * num_faces));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int f = 0; f < num_faces; ++f)
    for (int k = 0; k < 3; ++k)
      side[static_cast<size_t>(fill[static_cast<size_t>(topology.FE(f, k))]++)] = 3 * f + k;
}

// Orders the sides of edge (u, v) by the angle of their face around the edge (ties: in the given order), so
// that consecutive sides bound an empty wedge.
void sort_by_angle_around_edge(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int u, int v,
                               std::vector<int>& sides) {
  const Eigen::RowVector3d p = V.row(u);
  const Eigen::RowVector3d d = (V.row(v) - p).normalized();
  std::vector<Eigen::RowVector3d> w(sides.size());
  Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
  for (size_t i = 0; i < sides.size(); ++i) {
    const int f = sides[i] / 3, k = sides[i] % 3;
    const Eigen::RowVector3d c = V.row(F(f, k)) - p;
    w[i] = c - c.dot(d) * d; // the face's direction away from the edge
    if (x.squaredNorm() == 0.0) x = w[i];
  }
  const Eigen::RowVector3d y = d.cross(x);
  std::vector<double> angle(sides.size());
  for (size_t i = 0; i < sides.size(); ++i) angle[i] = std::atan2(w[i].dot(y), w[i].dot(x));
  std::vector<size_t> order(sides.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return angle[a] < angle[b]; });
  std::vector<int> sorted(sides.size());
  for (size_t i = 0; i < sides.size(); ++i) sorted[i] = sides[order[i]];
  sides.swap(sorted);
}

} // namespace

TuftedCover tufted_cover(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const EdgeTopology& topology) {
  const int nf = static_cast<int>(F.rows());
  TuftedCover cover;
  cover.twin.assign(static_cast<size_t>(6 * nf), -1);
  std::vector<int> start, side;
  sides_by_edge(topology, nf, start, side);
  std::vector<int> sides;
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e) {
    const int u = topology.E(e, 0), v = topology.E(e, 1);
    sides.assign(side.begin() + start[static_cast<size_t>(e)],
                 side.begin() + start[static_cast<size_t>(e) + 1]);
    cover.max_edge_faces = std::max(cover.max_edge_faces, static_cast<int>(sides.size()));
    // One or two faces close around the edge in any order; three and more need the geometric one.
    if (sides.size() > 2) sort_by_angle_around_edge(V, F, u, v, sides);
    // The copy of a face whose normal points towards increasing angle runs u -> v: the front copy where the
    // face runs u -> v. Across the wedge after face i, that copy meets the copy of face i + 1 facing back,
    // which runs v -> u: the two are glued with opposite directions, so the cover is oriented.
    const auto runs_forward = [&](int s) { return F(s / 3, (s % 3 + 1) % 3) == u; };
    const size_t count = sides.size();
    for (size_t i = 0; i < count; ++i) {
      const int s = sides[i], t = sides[(i + 1) % count];
      const int ahead = runs_forward(s) ? front_halfedge(s / 3, s % 3) : back_halfedge(s / 3, s % 3);
      const int behind = runs_forward(t) ? back_halfedge(t / 3, t % 3) : front_halfedge(t / 3, t % 3);
      cover.twin[static_cast<size_t>(ahead)] = behind;
      cover.twin[static_cast<size_t>(behind)] = ahead;
    }
  }
  // Cover corner 3 g + k at input vertex G(g, k); across each glued edge, the corners at either end of one
  // halfedge are the same cover vertex as the corners at the other end of its twin.
  Eigen::MatrixXi G(2 * nf, 3);
  for (int f = 0; f < nf; ++f) {
    G.row(2 * f) = F.row(f);
    G.row(2 * f + 1) << F(f, 0), F(f, 2), F(f, 1);
  }
  std::vector<int> join_a, join_b;
  join_a.reserve(static_cast<size_t>(6 * nf));
  join_b.reserve(static_cast<size_t>(6 * nf));
  for (int h = 0; h < 6 * nf; ++h) {
    const int t = cover.twin[static_cast<size_t>(h)];
    if (h > t) continue; // each glued pair once
    join_a.push_back(h);
    join_b.push_back(next_halfedge(t));
    join_a.push_back(next_halfedge(h));
    join_b.push_back(t);
  }
  int count = 0;
  const Eigen::VectorXi group = mesh_checks::group_pairs(join_a, join_b, 6 * nf, &count);
  cover.vertex.resize(count);
  cover.F.resize(2 * nf, 3);
  for (int c = 0; c < 6 * nf; ++c) {
    cover.F(c / 3, c % 3) = group(c);
    cover.vertex(group(c)) = G(c / 3, c % 3);
  }
  cover.V.resize(count, 3);
  for (int v = 0; v < count; ++v) cover.V.row(v) = V.row(cover.vertex(v));
  return cover;
}

// Walks around every vertex from one of its corners, both ways up to the boundary, and counts the corners
// reached against the vertex's own count. Walks are independent (a parallel loop over vertices) and read
// the topology only, where pinched_vertices groups all corners in one union-find pass (2.7 s at 2.77M
// vertices: docs/performance.md).
bool every_vertex_has_one_fan(const Eigen::MatrixXi& F, const EdgeTopology& t, int num_vertices) {
  const int nf = static_cast<int>(F.rows());
  std::vector<int> corners_at(static_cast<size_t>(num_vertices), 0),
      some_corner(static_cast<size_t>(num_vertices), -1);
  for (int c = 0; c < 3 * nf; ++c) {
    const int v = F(c / 3, c % 3);
    ++corners_at[static_cast<size_t>(v)];
    some_corner[static_cast<size_t>(v)] = c;
  }
  // The corner of v = F(f, k) in the face across the edge opposite corner `across` of f (an edge of f at v),
  // or -1 on the boundary. The two faces traverse the edge in opposite directions, so v sits in g at the
  // corner after the opposite one (`after` 1) or two after it (`after` 2).
  const auto turn = [&](int f, int k, int across, int after) {
    const int e = t.FE(f, across);
    if (t.face_count(e) < 2) return -1;
    const int side = t.EF(e, 0) == f && t.EK(e, 0) == across ? 1 : 0;
    const int g = t.EF(e, side), m = (t.EK(e, side) + after) % 3;
    return F(g, m) == F(f, k) ? 3 * g + m : -2; // -2: not the mesh the edge loop accepted
  };
  bool one_fan = true;
// loop_thread_count(): in arap_precompute this runs beside the analysis, which holds a core.
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(&& : one_fan)
  for (int v = 0; v < num_vertices; ++v) {
    const int start = some_corner[static_cast<size_t>(v)];
    if (start < 0 || !one_fan) continue;
    int reached = 1, c = start;
    // Forward: across the edge v -> F(f, k+1), opposite corner k+2; v is two after g's opposite corner.
    while (true) {
      c = turn(c / 3, c % 3, (c % 3 + 2) % 3, 2);
      if (c < 0 || c == start || reached > corners_at[static_cast<size_t>(v)]) break;
      ++reached;
    }
    if (c == -1) { // open: back from the start across the edge F(f, k+2) -> v, opposite corner k+1
      c = start;
      while (true) {
        c = turn(c / 3, c % 3, (c % 3 + 1) % 3, 1);
        if (c < 0 || reached > corners_at[static_cast<size_t>(v)]) break;
        ++reached;
      }
    }
    if (c == -2 || reached != corners_at[static_cast<size_t>(v)]) one_fan = false;
  }
  return one_fan;
}

bool edges_are_oriented_manifold(const Eigen::MatrixXi& F, const EdgeTopology& topology) {
  const Eigen::Index ne = topology.E.rows();
  for (Eigen::Index e = 0; e < ne; ++e) {
    if (topology.face_count(e) > 2) return false;
    if (topology.face_count(e) < 2) continue;
    const int f0 = topology.EF(e, 0), f1 = topology.EF(e, 1), k0 = topology.EK(e, 0), k1 = topology.EK(e, 1);
    if (F(f0, (k0 + 1) % 3) == F(f1, (k1 + 1) % 3)) return false; // both run the same way
  }
  return true;
}

bool is_oriented_manifold(const Eigen::MatrixXi& F, const EdgeTopology& topology, int num_vertices) {
  if (!edges_are_oriented_manifold(F, topology)) return false;
  // Most meshes have no vertex where fans meet: the walk says so without grouping corners. Where some
  // vertex has several fans, pinched_vertices tells closed fans (refused) from open ones (accepted).
  if (every_vertex_has_one_fan(F, topology, num_vertices)) return true;
  return mesh_checks::pinched_vertices(F, topology, num_vertices).closed.empty();
}

} // namespace iarap::detail
