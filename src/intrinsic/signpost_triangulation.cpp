#include "signpost_triangulation.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Angle opposite side a in a triangle with sides a, b, c; atan2 keeps needles accurate where acos fails.
double angle_from_lengths(double a, double b, double c) {
  const double four_area = 4.0 * triangle_area_from_lengths(a, b, c);
  return std::atan2(four_area, b * b + c * c - a * a);
}

std::string edge_name(int a, int b) { return "(" + std::to_string(a) + ", " + std::to_string(b) + ")"; }

} // namespace

double SignpostTriangulation::corner_angle(int h) const {
  return angle_from_lengths(halfedge_length(next_halfedge(h)), halfedge_length(h),
                            halfedge_length(prev_halfedge(h)));
}

double SignpostTriangulation::opposite_cotangent(int h) const {
  return cotangent_from_lengths(halfedge_length(h), halfedge_length(next_halfedge(h)),
                                halfedge_length(prev_halfedge(h)));
}

double SignpostTriangulation::cotan_weight(int e) const {
  const int h = edge_halfedge[static_cast<size_t>(e)];
  double w = 0.5 * opposite_cotangent(h);
  const int t = twin[static_cast<size_t>(h)];
  if (t >= 0) w += 0.5 * opposite_cotangent(t);
  return w;
}

SignpostTriangulation build_signpost_triangulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                   bool mollify, double mollify_epsilon) {
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(F.rows());
  if (F.cols() != 3) throw InputError("faces must have 3 columns, got " + std::to_string(F.cols()));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (F(f, k) < 0 || F(f, k) >= nv)
        throw InputError("face " + std::to_string(f) + " uses vertex " + std::to_string(F(f, k)) +
                         "; mesh has " + std::to_string(nv));
    }
    if (F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 2) == F(f, 0))
      throw TopologyError("face " + std::to_string(f) + " repeats a vertex");
  }
  if (!V.allFinite()) throw InputError("vertex coordinates contain NaN or Inf");

  const EdgeTopology topo = edge_topology(F, nv);
  const int ne = static_cast<int>(topo.E.rows());
  SignpostTriangulation tri;
  tri.num_vertices = nv;
  tri.corner_vertex.resize(static_cast<size_t>(3 * nf));
  tri.twin.assign(static_cast<size_t>(3 * nf), -1);
  tri.edge.resize(static_cast<size_t>(3 * nf));
  tri.edge_halfedge.assign(static_cast<size_t>(ne), -1);
  tri.original_edge.resize(static_cast<size_t>(ne));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      tri.corner_vertex[static_cast<size_t>(3 * f + k)] = F(f, k);
      tri.edge[static_cast<size_t>(3 * f + k)] = topo.FE(f, (k + 2) % 3);
    }
  for (int e = 0; e < ne; ++e) {
    tri.original_edge[static_cast<size_t>(e)] = e;
    if (topo.face_count(e) > 2)
      throw TopologyError("non-manifold edge " + edge_name(topo.E(e, 0), topo.E(e, 1)) + " is shared by " +
                          std::to_string(topo.face_count(e)) + " faces");
    const int h0 = 3 * topo.EF(e, 0) + (topo.EK(e, 0) + 1) % 3;
    tri.edge_halfedge[static_cast<size_t>(e)] = h0;
    if (topo.face_count(e) == 2) {
      const int h1 = 3 * topo.EF(e, 1) + (topo.EK(e, 1) + 1) % 3;
      if (tri.tail(h0) == tri.tail(h1))
        throw TopologyError("faces " + std::to_string(topo.EF(e, 0)) + " and " + std::to_string(topo.EF(e, 1)) +
                            " are inconsistently oriented across edge " + edge_name(topo.E(e, 0), topo.E(e, 1)));
      tri.twin[static_cast<size_t>(h0)] = h1;
      tri.twin[static_cast<size_t>(h1)] = h0;
      if (tri.tail(h1) < tri.tail(h0)) tri.edge_halfedge[static_cast<size_t>(e)] = h1;
    }
  }

  // Edge lengths, then the mollification of Sharp & Crane 2020: one delta for all edges so that every
  // triangle inequality holds with margin eps.
  tri.length.resize(static_cast<size_t>(ne));
  double mean_length = 0.0;
  for (int e = 0; e < ne; ++e) {
    tri.length[static_cast<size_t>(e)] = (V.row(topo.E(e, 0)) - V.row(topo.E(e, 1))).norm();
    mean_length += tri.length[static_cast<size_t>(e)];
  }
  mean_length /= std::max(ne, 1);
  const double eps = mollify_epsilon * mean_length;
  double delta = 0.0;
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const double a = tri.halfedge_length(3 * f + k), b = tri.halfedge_length(3 * f + (k + 1) % 3),
                   c = tri.halfedge_length(3 * f + (k + 2) % 3);
      const double need = eps - (b + c - a);
      if (need > 0 && !mollify)
        throw TopologyError("face " + std::to_string(f) + " is degenerate (triangle inequality margin " +
                            std::to_string(b + c - a) + " below " + std::to_string(eps) +
                            "); enable intrinsic mollification or repair the mesh");
      delta = std::max(delta, need);
    }
  }
  if (delta > 0)
    for (double& l : tri.length) l += delta;
  tri.mollify_delta = delta;

  // Angle sums and signposts: sweep each vertex's fans counter-clockwise. A fan that ends on the boundary
  // starts at its outgoing boundary halfedge, so its angles run from 0 to its total without wrapping.
  // A vertex where several open fans meet (a "bowtie", common in scanned meshes) keeps one rotation cell;
  // its fans get disjoint angle ranges separated by a gap, so a signpost never points between fans.
  std::vector<int> outgoing(static_cast<size_t>(nv), 0);
  for (int h = 0; h < 3 * nf; ++h) ++outgoing[static_cast<size_t>(tri.tail(h))];
  std::vector<char> swept(static_cast<size_t>(3 * nf), 0);
  std::vector<int> fans(static_cast<size_t>(nv), 0);
  std::vector<char> closed_fan(static_cast<size_t>(nv), 0);
  tri.phi.assign(static_cast<size_t>(3 * nf), 0.0);
  tri.vertex_angle_sum.assign(static_cast<size_t>(nv), 0.0);
  tri.boundary_vertex.assign(static_cast<size_t>(nv), 0);
  auto sweep = [&](int h0) {
    const int v = tri.tail(h0);
    double angle = tri.vertex_angle_sum[static_cast<size_t>(v)];
    if (fans[static_cast<size_t>(v)] > 0) angle += 1.0; // gap between fans
    int h = h0;
    while (true) {
      swept[static_cast<size_t>(h)] = 1;
      tri.phi[static_cast<size_t>(h)] = angle;
      angle += tri.corner_angle(h);
      const int t = tri.twin[static_cast<size_t>(prev_halfedge(h))];
      if (t < 0) break;
      if (t == h0) {
        closed_fan[static_cast<size_t>(v)] = 1;
        break;
      }
      h = t;
    }
    tri.vertex_angle_sum[static_cast<size_t>(v)] = angle;
    ++fans[static_cast<size_t>(v)];
  };
  for (int h = 0; h < 3 * nf; ++h) // open fans first, from their boundary halfedge
    if (tri.twin[static_cast<size_t>(h)] < 0) {
      tri.boundary_vertex[static_cast<size_t>(tri.tail(h))] = 1;
      sweep(h);
    }
  for (int h = 0; h < 3 * nf; ++h)
    if (!swept[static_cast<size_t>(h)]) sweep(h);
  for (int v = 0; v < nv; ++v)
    if (fans[static_cast<size_t>(v)] > 1 && closed_fan[static_cast<size_t>(v)])
      throw TopologyError("non-manifold vertex " + std::to_string(v) + ": a closed fan of faces and " +
                          std::to_string(fans[static_cast<size_t>(v)] - 1) +
                          " more fans meet there (two surfaces touching at a point)");
  return tri;
}

bool flip_edge(SignpostTriangulation& tri, int e) {
  auto& twin = tri.twin;
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  const int t = twin[static_cast<size_t>(h)];
  if (t < 0) return false;
  const int f0 = h / 3, f1 = t / 3;
  if (f0 == f1) return false;
  // Before: f0 = (a, b, c) with h = a->b, h1 = b->c, h2 = c->a; f1 = (b, a, d) with t = b->a, t1 = a->d, t2 = d->b.
  const int h1 = next_halfedge(h), h2 = prev_halfedge(h), t1 = next_halfedge(t), t2 = prev_halfedge(t);
  const int a = tri.tail(h), b = tri.tail(t), c = tri.tail(h2), d = tri.tail(t2);
  const int e_bc = tri.edge[static_cast<size_t>(h1)], e_ca = tri.edge[static_cast<size_t>(h2)];
  const int e_ad = tri.edge[static_cast<size_t>(t1)], e_db = tri.edge[static_cast<size_t>(t2)];
  if (e_bc == e || e_ca == e || e_ad == e || e_db == e) return false;
  // The quad must be convex at a and b for the new diagonal to stay inside it.
  if (tri.corner_angle(h) + tri.corner_angle(t1) >= kPi || tri.corner_angle(t) + tri.corner_angle(h1) >= kPi)
    return false;

  // New length from the planar layout of the two triangles on either side of (a, b).
  const double l_ab = tri.length[static_cast<size_t>(e)];
  const double l_bc = tri.halfedge_length(h1), l_ca = tri.halfedge_length(h2);
  const double l_ad = tri.halfedge_length(t1), l_db = tri.halfedge_length(t2);
  const double cx = (l_ca * l_ca - l_bc * l_bc + l_ab * l_ab) / (2 * l_ab);
  const double cy = std::sqrt(std::max(l_ca * l_ca - cx * cx, 0.0));
  const double dx = (l_ad * l_ad - l_db * l_db + l_ab * l_ab) / (2 * l_ab);
  const double dy = -std::sqrt(std::max(l_ad * l_ad - dx * dx, 0.0));
  const double l_cd = std::hypot(cx - dx, cy - dy);

  // Old halfedge -> new slot, so that twins pointing into the two faces follow their halfedge.
  const int n_ca = 3 * f0 + 0, n_ad = 3 * f0 + 1, n_dc = 3 * f0 + 2;
  const int n_db = 3 * f1 + 0, n_bc = 3 * f1 + 1, n_cd = 3 * f1 + 2;
  auto moved = [&](int x) {
    if (x == h1) return n_bc;
    if (x == h2) return n_ca;
    if (x == t1) return n_ad;
    if (x == t2) return n_db;
    return x;
  };
  const int x_bc = moved(twin[static_cast<size_t>(h1)]), x_ca = moved(twin[static_cast<size_t>(h2)]);
  const int x_ad = moved(twin[static_cast<size_t>(t1)]), x_db = moved(twin[static_cast<size_t>(t2)]);
  const double phi_ca = tri.phi[static_cast<size_t>(h2)], phi_ad = tri.phi[static_cast<size_t>(t1)];
  const double phi_db = tri.phi[static_cast<size_t>(t2)], phi_bc = tri.phi[static_cast<size_t>(h1)];

  auto set = [&](int slot, int vertex, int edge_id, int twin_slot, double phi) {
    tri.corner_vertex[static_cast<size_t>(slot)] = vertex;
    tri.edge[static_cast<size_t>(slot)] = edge_id;
    twin[static_cast<size_t>(slot)] = twin_slot;
    tri.phi[static_cast<size_t>(slot)] = phi;
    if (twin_slot >= 0) twin[static_cast<size_t>(twin_slot)] = slot;
  };
  // After: f0 = (c, a, d), f1 = (d, b, c).
  set(n_ca, c, e_ca, x_ca, phi_ca);
  set(n_ad, a, e_ad, x_ad, phi_ad);
  set(n_db, d, e_db, x_db, phi_db);
  set(n_bc, b, e_bc, x_bc, phi_bc);
  tri.length[static_cast<size_t>(e)] = l_cd;
  set(n_dc, d, e, n_cd, 0.0);
  set(n_cd, c, e, n_dc, 0.0);
  tri.edge_halfedge[static_cast<size_t>(e)] = c <= d ? n_cd : n_dc;
  for (int s : {n_ca, n_ad, n_db, n_bc}) {
    // edge_halfedge: of an edge's two halfedges, the one with the lower tail vertex (E(e,0) <= E(e,1)).
    const int x = twin[static_cast<size_t>(s)];
    const int edge_id = tri.edge[static_cast<size_t>(s)];
    int best = s;
    if (x >= 0 && (tri.tail(x) < tri.tail(s) || (tri.tail(x) == tri.tail(s) && x < s))) best = x;
    tri.edge_halfedge[static_cast<size_t>(edge_id)] = best;
  }
  // Signposts of the new diagonal: rotate from the neighbouring halfedge by the new corner angle.
  auto wrap = [&](int v, double angle) {
    const double theta = tri.vertex_angle_sum[static_cast<size_t>(v)];
    if (tri.boundary_vertex[static_cast<size_t>(v)]) return std::min(angle, theta);
    return angle >= theta ? angle - theta : angle;
  };
  tri.phi[static_cast<size_t>(n_cd)] = wrap(c, phi_ca + tri.corner_angle(n_ca));
  tri.phi[static_cast<size_t>(n_dc)] = wrap(d, phi_db + tri.corner_angle(n_db));
  tri.original_edge[static_cast<size_t>(e)] = -1;
  return true;
}

int count_non_delaunay(const SignpostTriangulation& tri, double tolerance) {
  int count = 0;
  for (int e = 0; e < tri.num_edges(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int t = tri.twin[static_cast<size_t>(h)];
    if (t < 0) continue;
    if (tri.opposite_cotangent(h) + tri.opposite_cotangent(t) < -tolerance) ++count;
  }
  return count;
}

FlipStats flip_to_delaunay(SignpostTriangulation& tri, double tolerance) {
  FlipStats stats;
  stats.non_delaunay_before = count_non_delaunay(tri, tolerance);
  const int ne = tri.num_edges();
  std::vector<int> stack(static_cast<size_t>(ne));
  std::vector<char> queued(static_cast<size_t>(ne), 1);
  for (int e = 0; e < ne; ++e) stack[static_cast<size_t>(e)] = ne - 1 - e;
  // Each flip strictly lowers the Dirichlet energy of the piecewise-linear interpolant (Rippa, Bobenko &
  // Springborn), so the loop ends; the cap only guards against a numerical cycle.
  const long max_flips = 1000L * ne + 1000000L;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    queued[static_cast<size_t>(e)] = 0;
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    const int t = tri.twin[static_cast<size_t>(h)];
    if (t < 0 || tri.opposite_cotangent(h) + tri.opposite_cotangent(t) >= -tolerance) continue;
    if (!flip_edge(tri, e)) continue;
    if (++stats.flips > max_flips)
      throw SolverError("intrinsic Delaunay flipping did not terminate after " + std::to_string(max_flips) +
                        " flips (numerical cycle)");
    const int g = tri.edge_halfedge[static_cast<size_t>(e)];
    for (int s : {next_halfedge(g), prev_halfedge(g), next_halfedge(tri.twin[static_cast<size_t>(g)]),
                  prev_halfedge(tri.twin[static_cast<size_t>(g)])}) {
      const int n = tri.edge[static_cast<size_t>(s)];
      if (!queued[static_cast<size_t>(n)]) {
        queued[static_cast<size_t>(n)] = 1;
        stack.push_back(n);
      }
    }
  }
  stats.non_delaunay_after = count_non_delaunay(tri, tolerance);
  return stats;
}

} // namespace iarap::detail
