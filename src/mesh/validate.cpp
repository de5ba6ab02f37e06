#include "iarap/mesh/validate.h"

#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/repair.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace iarap {

namespace {

// Relative thresholds of the report, documented in validate.h.
constexpr double zero_area_factor = 1e-12;  // times bbox_diagonal^2
constexpr double coincident_factor = 1e-12; // times bbox_diagonal
// Cotangents are dimensionless; exact right angles of regular grids compute to +-1e-16, not a real violation.
constexpr double delaunay_tolerance = 1e-12;

// Connected groups of the pairs (a_i, b_i) over n items, through vertex_components on degenerate "faces".
Eigen::VectorXi group_pairs(const std::vector<int>& a, const std::vector<int>& b, int n, int* count) {
  Eigen::MatrixXi pairs(static_cast<Eigen::Index>(a.size()), 3);
  for (std::size_t i = 0; i < a.size(); ++i) pairs.row(static_cast<Eigen::Index>(i)) << a[i], b[i], b[i];
  return vertex_components(pairs, n, count);
}

// Per face component (faces joined through manifold edges): whether its faces can be oriented
// consistently, found by propagating a flip bit face to face: across an edge whose two faces run the same
// way the bit changes, else it stays; a face reached with both bits lies on a non-orientable surface
// (Moebius strip, Klein bottle). Returns the number of such components; first_bad gets one of their faces.
int non_orientable_components(const Eigen::MatrixXi& G, const EdgeTopology& t, int* first_bad) {
  const int ng = static_cast<int>(G.rows());
  std::vector<signed char> flip(static_cast<std::size_t>(ng), -1);
  std::vector<int> stack;
  int bad = 0;
  for (int seed = 0; seed < ng; ++seed) {
    if (flip[static_cast<std::size_t>(seed)] >= 0) continue;
    flip[static_cast<std::size_t>(seed)] = 0;
    stack.assign(1, seed);
    bool orientable = true;
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int e = t.FE(g, k);
        if (t.face_count(e) != 2) continue;
        const int side = t.EF(e, 0) == g ? 0 : 1;
        const int h = t.EF(e, 1 - side), kh = t.EK(e, 1 - side);
        const bool same_direction = G(g, (k + 1) % 3) == G(h, (kh + 1) % 3);
        const signed char want = static_cast<signed char>(flip[static_cast<std::size_t>(g)] ^ same_direction);
        signed char& have = flip[static_cast<std::size_t>(h)];
        if (have < 0) {
          have = want;
          stack.push_back(h);
        } else if (have != want && orientable) {
          orientable = false;
          if (bad == 0 && first_bad) *first_bad = h;
        }
      }
    }
    bad += !orientable;
  }
  return bad;
}

std::string plural(int n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

} // namespace

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
  const int nv = r.vertices, nf = r.faces;
  if (nf == 0) r.errors.push_back("mesh has no faces");

  // ---- coordinates
  int first_bad_vertex = -1;
  for (int v = 0; v < nv; ++v)
    if (!V.row(v).allFinite()) {
      if (r.non_finite_coordinates++ == 0) first_bad_vertex = v;
    }
  if (r.non_finite_coordinates > 0)
    r.errors.push_back(plural(r.non_finite_coordinates, "vertex has", "vertices have") +
                       " a NaN or Inf coordinate; first: vertex " + std::to_string(first_bad_vertex));
  r.bbox_diagonal = bounding_box_diagonal(V); // in units of `scale` until the end

  // ---- face indices; only faces with three distinct in-range indices enter the topological checks
  std::vector<int> good;
  good.reserve(static_cast<std::size_t>(nf));
  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  int first_range_face = -1, first_range_index = 0, first_repeat_face = -1;
  for (int f = 0; f < nf; ++f) {
    bool in_range = true;
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k);
      if (i < 0 || i >= nv) {
        in_range = false;
        if (r.out_of_range_indices++ == 0) {
          first_range_face = f;
          first_range_index = i;
        }
      }
    }
    if (!in_range) continue;
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(F(f, k))] = 1;
    if (F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2)) {
      if (r.repeated_vertex_faces++ == 0) first_repeat_face = f;
      continue;
    }
    good.push_back(f);
  }
  if (r.out_of_range_indices > 0)
    r.errors.push_back(plural(r.out_of_range_indices, "face index is", "face indices are") +
                       " out of range; first: face " + std::to_string(first_range_face) + " uses vertex " +
                       std::to_string(first_range_index) + "; mesh has " + std::to_string(nv) + " vertices");
  if (r.repeated_vertex_faces > 0)
    r.errors.push_back(
        plural(r.repeated_vertex_faces, "face repeats", "faces repeat") + " a vertex; first: face " +
        std::to_string(first_repeat_face) + " (" + std::to_string(F(first_repeat_face, 0)) + ", " +
        std::to_string(F(first_repeat_face, 1)) + ", " + std::to_string(F(first_repeat_face, 2)) + ")");
  int first_unused = -1;
  for (int v = 0; v < nv; ++v)
    if (!used[static_cast<std::size_t>(v)] && r.unreferenced_vertices++ == 0) first_unused = v;
  if (r.unreferenced_vertices > 0)
    r.warnings.push_back(plural(r.unreferenced_vertices, "vertex is", "vertices are") +
                         " used by no face; first: vertex " + std::to_string(first_unused) +
                         " (repair removes them: `iarap deform --repair`, repair_mesh)");

  const int ng = static_cast<int>(good.size());
  Eigen::MatrixXi G(ng, 3);
  for (int g = 0; g < ng; ++g) G.row(g) = F.row(good[static_cast<std::size_t>(g)]);

  // ---- zero-area faces
  const double min_area = zero_area_factor * r.bbox_diagonal * r.bbox_diagonal;
  int first_flat = -1;
  for (int g = 0; g < ng; ++g) {
    const Eigen::RowVector3d a = V.row(G(g, 0)), b = V.row(G(g, 1)), c = V.row(G(g, 2));
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (area <= min_area && r.zero_area_faces++ == 0) first_flat = good[static_cast<std::size_t>(g)];
  }
  if (r.zero_area_faces > 0)
    r.warnings.push_back(plural(r.zero_area_faces, "face has", "faces have") +
                         " zero area (<= 1e-12 x bbox diagonal^2); first: face " +
                         std::to_string(first_flat) +
                         " (repair drops them: `iarap deform --repair`, repair_mesh with remove_zero_area)");

  // ---- edges: boundary, non-manifold, orientation, Delaunay
  const EdgeTopology t = edge_topology(G, nv);
  const int ne = static_cast<int>(t.E.rows());
  r.edges = ne;
  const Eigen::MatrixXd C = face_cotangents(V, G);
  int first_nm_edge = -1, first_flip_edge = -1;
  for (int e = 0; e < ne; ++e) {
    const int count = t.face_count(e);
    if (count == 1) ++r.boundary_edges;
    if (count > 2 && r.non_manifold_edges++ == 0) first_nm_edge = e;
    if (count != 2) continue;
    const int f0 = t.EF(e, 0), f1 = t.EF(e, 1), k0 = t.EK(e, 0), k1 = t.EK(e, 1);
    // Each face runs along the edge from corner k+1 to corner k+2; consistent neighbours run opposite ways.
    if (G(f0, (k0 + 1) % 3) == G(f1, (k1 + 1) % 3) && r.inconsistently_oriented_edges++ == 0)
      first_flip_edge = e;
    if (C(f0, k0) + C(f1, k1) < -delaunay_tolerance) ++r.non_delaunay_edges;
  }
  const auto edge_name = [&](int e) {
    return "edge (" + std::to_string(t.E(e, 0)) + ", " + std::to_string(t.E(e, 1)) + ")";
  };
  if (r.non_manifold_edges > 0)
    r.errors.push_back(plural(r.non_manifold_edges, "edge is", "edges are") +
                       " non-manifold (3 or more faces); first: " + edge_name(first_nm_edge) + " with " +
                       std::to_string(t.face_count(first_nm_edge)) + " faces");
  int first_non_orientable_face = -1;
  r.non_orientable_components = non_orientable_components(G, t, &first_non_orientable_face);
  if (r.inconsistently_oriented_edges > 0) {
    const std::string where = "; first: " + edge_name(first_flip_edge) + " between faces " +
                              std::to_string(good[static_cast<std::size_t>(t.EF(first_flip_edge, 0))]) +
                              " and " +
                              std::to_string(good[static_cast<std::size_t>(t.EF(first_flip_edge, 1))]);
    if (r.non_orientable_components > 0)
      r.errors.push_back("the surface is non-orientable (" +
                         plural(r.non_orientable_components, "component has", "components have") +
                         " no consistent orientation, like a Moebius strip or a Klein bottle; first: the "
                         "component of face " +
                         std::to_string(good[static_cast<std::size_t>(first_non_orientable_face)]) +
                         "): no choice of face orientations fixes it, and ARAP needs one; " +
                         plural(r.inconsistently_oriented_edges, "edge joins", "edges join") +
                         " faces oriented in the same direction" + where);
    else
      r.errors.push_back(plural(r.inconsistently_oriented_edges, "edge joins", "edges join") +
                         " inconsistently oriented faces" + where +
                         "; the surface is orientable: reverse the faces of one side (re-export with "
                         "consistent normals)");
  }

  // ---- non-manifold vertices: join the corners of a vertex in faces sharing an edge at it; more than one
  // group of corners at a vertex means more than one fan.
  std::vector<int> join_a, join_b;
  join_a.reserve(static_cast<std::size_t>(6 * ng));
  join_b.reserve(static_cast<std::size_t>(6 * ng));
  std::vector<int> first_corner(static_cast<std::size_t>(2 * ne), -1); // per edge end: a corner seen there
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) {
      const int e = t.FE(g, k);
      for (int end = 0; end < 2; ++end) {
        const int corner_k = G(g, (k + 1) % 3) == t.E(e, end) ? (k + 1) % 3 : (k + 2) % 3;
        const int corner = 3 * g + corner_k;
        int& seen = first_corner[static_cast<std::size_t>(2 * e + end)];
        if (seen < 0) {
          seen = corner;
        } else {
          join_a.push_back(seen);
          join_b.push_back(corner);
        }
      }
    }
  const Eigen::VectorXi fan = group_pairs(join_a, join_b, 3 * ng, nullptr);
  std::vector<int> fan_of(static_cast<std::size_t>(nv), -1);
  std::vector<char> pinched(static_cast<std::size_t>(nv), 0);
  for (int c = 0; c < 3 * ng; ++c) {
    const int v = G(c / 3, c % 3);
    int& seen = fan_of[static_cast<std::size_t>(v)];
    if (seen < 0)
      seen = fan(c);
    else if (seen != fan(c))
      pinched[static_cast<std::size_t>(v)] = 1;
  }
  // A pinched vertex whose fans are all open (each fan ends on two boundary edges) is where separate
  // sheets touch, common in scans: ARAP keeps one rotation cell there and the intrinsic triangulation gives
  // each fan its own angle range, so it is only a warning. A closed fan touching another is an error.
  std::vector<std::pair<int, int>> vertex_fans;
  for (int c = 0; c < 3 * ng; ++c) {
    const int v = G(c / 3, c % 3);
    if (pinched[static_cast<std::size_t>(v)]) vertex_fans.emplace_back(v, fan(c));
  }
  std::sort(vertex_fans.begin(), vertex_fans.end());
  vertex_fans.erase(std::unique(vertex_fans.begin(), vertex_fans.end()), vertex_fans.end());
  std::vector<int> fan_count(static_cast<std::size_t>(nv), 0), boundary_at(static_cast<std::size_t>(nv), 0);
  for (const auto& vf : vertex_fans) ++fan_count[static_cast<std::size_t>(vf.first)];
  for (int e = 0; e < ne; ++e)
    if (t.face_count(e) == 1) {
      ++boundary_at[static_cast<std::size_t>(t.E(e, 0))];
      ++boundary_at[static_cast<std::size_t>(t.E(e, 1))];
    }
  int first_pinched = -1, first_open_pinched = -1, open_pinched = 0;
  for (int v = 0; v < nv; ++v) {
    if (!pinched[static_cast<std::size_t>(v)]) continue;
    if (r.non_manifold_vertices++ == 0) first_pinched = v;
    if (boundary_at[static_cast<std::size_t>(v)] == 2 * fan_count[static_cast<std::size_t>(v)] &&
        open_pinched++ == 0)
      first_open_pinched = v;
  }
  if (open_pinched > 0)
    r.warnings.push_back(plural(open_pinched, "vertex joins", "vertices join") +
                         " several open fans of faces (sheets touching at a point; handled as one rotation "
                         "cell); first: vertex " +
                         std::to_string(first_open_pinched));
  if (r.non_manifold_vertices > open_pinched) {
    for (int v = 0; v < nv; ++v)
      if (pinched[static_cast<std::size_t>(v)] &&
          boundary_at[static_cast<std::size_t>(v)] != 2 * fan_count[static_cast<std::size_t>(v)]) {
        first_pinched = v;
        break;
      }
    r.errors.push_back(plural(r.non_manifold_vertices - open_pinched, "vertex is", "vertices are") +
                       " non-manifold (a closed fan of faces touches another fan there); first: vertex " +
                       std::to_string(first_pinched));
  }

  // ---- components and boundary loops
  int raw_components = 0;
  const Eigen::VectorXi component = vertex_components(G, nv, &raw_components);
  std::vector<char> in_mesh(static_cast<std::size_t>(nv), 0);
  for (int g = 0; g < ng; ++g)
    for (int k = 0; k < 3; ++k) in_mesh[static_cast<std::size_t>(G(g, k))] = 1;
  std::vector<int> dense(static_cast<std::size_t>(raw_components), -1); // component id among face components
  for (int v = 0; v < nv; ++v)
    if (in_mesh[static_cast<std::size_t>(v)] && dense[static_cast<std::size_t>(component(v))] < 0)
      dense[static_cast<std::size_t>(component(v))] = r.components++;
  const auto comp = [&](int v) { return dense[static_cast<std::size_t>(component(v))]; };

  std::vector<int> bound_a, bound_b;
  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (int e = 0; e < ne; ++e)
    if (t.face_count(e) == 1) {
      bound_a.push_back(t.E(e, 0));
      bound_b.push_back(t.E(e, 1));
      on_boundary[static_cast<std::size_t>(t.E(e, 0))] = on_boundary[static_cast<std::size_t>(t.E(e, 1))] = 1;
    }
  int raw_loops = 0;
  const Eigen::VectorXi loop = group_pairs(bound_a, bound_b, nv, &raw_loops);
  std::vector<char> loop_seen(static_cast<std::size_t>(raw_loops), 0);
  std::vector<std::int64_t> loops_in(static_cast<std::size_t>(r.components), 0),
      chi(static_cast<std::size_t>(r.components), 0);
  for (int v = 0; v < nv; ++v) {
    if (!in_mesh[static_cast<std::size_t>(v)]) continue;
    ++chi[static_cast<std::size_t>(comp(v))];
    if (on_boundary[static_cast<std::size_t>(v)] && !loop_seen[static_cast<std::size_t>(loop(v))]) {
      loop_seen[static_cast<std::size_t>(loop(v))] = 1;
      ++loops_in[static_cast<std::size_t>(comp(v))];
      ++r.boundary_loops;
    }
  }

  // ---- genus: chi = V - E + F per component, genus = (2 - chi - b) / 2
  for (int e = 0; e < ne; ++e) --chi[static_cast<std::size_t>(comp(t.E(e, 0)))];
  for (int g = 0; g < ng; ++g) ++chi[static_cast<std::size_t>(comp(G(g, 0)))];
  // Only for an orientable manifold: a non-orientable surface of even 2 - chi - b (the Klein bottle: 0 - 0
  // + 2) would otherwise pass for an orientable one of genus (2 - chi - b) / 2.
  if (r.non_manifold_edges == 0 && r.non_manifold_vertices == 0 && r.non_orientable_components == 0) {
    std::int64_t genus = 0;
    bool valid = true;
    for (int c = 0; c < r.components; ++c) {
      const std::int64_t twice = 2 - chi[static_cast<std::size_t>(c)] - loops_in[static_cast<std::size_t>(c)];
      if (twice % 2 != 0 || twice < 0) valid = false;
      genus += twice / 2;
    }
    if (valid) r.genus = static_cast<int>(genus);
  }

  // ---- coincident vertices
  const Eigen::VectorXi representative = weld_representatives(V, coincident_factor * r.bbox_diagonal);
  int first_coincident = -1;
  for (int v = 0; v < nv; ++v)
    if (representative(v) != v && r.coincident_vertices++ == 0) first_coincident = v;
  if (r.coincident_vertices > 0)
    r.warnings.push_back(plural(r.coincident_vertices, "vertex coincides", "vertices coincide") +
                         " with an earlier vertex (within 1e-12 x bbox diagonal); first: vertex " +
                         std::to_string(first_coincident) + " at the position of vertex " +
                         std::to_string(representative(first_coincident)) +
                         " (repair welds them: `iarap deform --repair`, repair_mesh)");
  if (ng > 1 && r.components == ng)
    r.warnings.push_back("the mesh falls apart into one component per face (" + std::to_string(ng) +
                         "): faces share no vertices, as in an unwelded triangle soup (STL); repair welds it "
                         "(`iarap deform --repair`, repair_mesh)");
  r.bbox_diagonal *= scale;
  return r;
}

} // namespace iarap
