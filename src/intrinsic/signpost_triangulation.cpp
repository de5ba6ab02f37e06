#include "signpost_triangulation.h"
#include "../core/math_constants.h"
#include "../mesh/face_index_range.h"
#include "upper_half_angle.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace iarap::detail {

namespace {

std::string edge_name(int a, int b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

// d[k] = 2 l_a l_b cos(angle opposite halfedge k) by the law of cosines, with l[k] the length of halfedge
// 3f + k; returns 4 x the face's area.
double face_terms(const double (&l)[3], double (&d)[3]) {
  const double four_area = 4.0 * triangle_area_from_lengths(l[0], l[1], l[2]);
  for (int k = 0; k < 3; ++k)
    d[k] = l[(k + 1) % 3] * l[(k + 1) % 3] + l[(k + 2) % 3] * l[(k + 2) % 3] - l[k] * l[k];
  return four_area;
}

// Writes the corner angle at the tail of each halfedge of the face to a[0..2] (face_terms gave d and
// four_area). atan2 keeps needles accurate where acos fails; the corner at the tail of halfedge k faces
// halfedge k + 1. The largest angle (facing the longest side, at least pi/3) is pi minus the other two: no
// accuracy lost, one atan2 saved per face.
void corner_angles(const double (&l)[3], const double (&d)[3], double four_area, double* a) {
  const int longest = l[0] >= l[1] ? (l[0] >= l[2] ? 0 : 2) : (l[1] >= l[2] ? 1 : 2);
  const int big = (longest + 2) % 3, k1 = (big + 1) % 3, k2 = (big + 2) % 3;
  a[k1] = upper_half_angle(four_area, d[(k1 + 1) % 3]);
  a[k2] = upper_half_angle(four_area, d[(k2 + 1) % 3]);
  a[big] = std::max(kPi - a[k1] - a[k2], 0.0);
}

// Writes the cotangents of face f's three halfedges (of the angle opposite each) from the lengths l of those
// halfedges; returns 4 x its area (d as in face_terms).
double write_face_cotangents(SignpostTriangulation& tri, int f, const double (&l)[3], double (&d)[3]) {
  const double four_area = face_terms(l, d);
  for (int k = 0; k < 3; ++k) tri.cot[static_cast<size_t>(3 * f + k)] = d[k] / four_area;
  return four_area;
}

// The same from the current lengths, which it writes to l.
double set_face_cotangents(SignpostTriangulation& tri, int f, double (&l)[3], double (&d)[3]) {
  for (int k = 0; k < 3; ++k) l[k] = tri.halfedge_length(3 * f + k);
  return write_face_cotangents(tri, f, l, d);
}

// |V_i - V_j|, one expression for every length of the input (the per-edge and the per-face passes agree
// bit for bit).
double input_distance(const Eigen::MatrixXd& V, int i, int j) {
  return std::sqrt((V(i, 0) - V(j, 0)) * (V(i, 0) - V(j, 0)) + (V(i, 1) - V(j, 1)) * (V(i, 1) - V(j, 1)) +
                   (V(i, 2) - V(j, 2)) * (V(i, 2) - V(j, 2)));
}

// The checks of the input that come before its topology: indices, repeated vertices, finite coordinates.
// Parallel scans that keep the first offending index; the error is thrown afterwards.
void check_signpost_input(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(F.rows());
  if (F.cols() != 3) throw InputError("faces must have 3 columns, got " + std::to_string(F.cols()));
  int bad_face = nf;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(min : bad_face)
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= nv || F(f, k) == F(f, (k + 1) % 3)) bad_face = std::min(bad_face, f);
  if (bad_face < nf) {
    require_face_indices_in_range(F.topRows(bad_face + 1), nv, "", bad_face);
    throw TopologyError("face " + std::to_string(bad_face) + " repeats a vertex");
  }
  if (!V.allFinite()) throw InputError("vertex coordinates contain NaN or Inf");
}

// Edges with one face. Boundary refinement splits some: each split adds a face, a vertex and two edges.
int boundary_edge_count(const EdgeTopology& topo) {
  const int ne = static_cast<int>(topo.E.rows());
  int count = 0;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(+ : count)
  for (int e = 0; e < ne; ++e) count += topo.face_count(e) == 1;
  return count;
}

} // namespace

void SignpostTriangulation::update_face_cotangents(int f) {
  double l[3], d[3];
  set_face_cotangents(*this, f, l, d);
}

void SignpostTriangulation::update_face_geometry(int f) {
  double l[3], d[3];
  const double four_area = set_face_cotangents(*this, f, l, d);
  corner_angles(l, d, four_area, angle.data() + 3 * static_cast<size_t>(f));
}

SignpostInput signpost_input(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                             bool room_for_boundary_splits) {
  check_signpost_input(V, F);
  const int nf = static_cast<int>(F.rows());
  auto topology = std::make_shared<const EdgeTopology>(edge_topology(F, static_cast<int>(V.rows())));
  const EdgeTopology& topo = *topology;
  const int ne = static_cast<int>(topo.E.rows());
  const size_t splits = room_for_boundary_splits ? static_cast<size_t>(boundary_edge_count(topo)) : 0;
  SignpostInput input;
  // With the room the build reserves (it takes both vectors over).
  input.length.reserve(static_cast<size_t>(ne) + 2 * splits);
  input.length.resize(static_cast<size_t>(ne));
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int e = 0; e < ne; ++e)
    input.length[static_cast<size_t>(e)] = input_distance(V, topo.E(e, 0), topo.E(e, 1));
  auto C = std::make_shared<Eigen::MatrixXd>(nf, 3);
  input.angle.reserve(3 * (static_cast<size_t>(nf) + splits));
  input.angle.resize(static_cast<size_t>(3 * nf));
  // The arithmetic of update_face_geometry on the build's lengths (halfedge k of face f is edge
  // FE(f, k + 2)), and C(f, k + 2) is the cotangent opposite halfedge k: the values the build and
  // face_cotangents compute.
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int f = 0; f < nf; ++f) {
    double l[3], d[3];
    for (int k = 0; k < 3; ++k) l[k] = input.length[static_cast<size_t>(topo.FE(f, (k + 2) % 3))];
    const double four_area = face_terms(l, d);
    for (int k = 0; k < 3; ++k) (*C)(f, (k + 2) % 3) = d[k] / four_area;
    corner_angles(l, d, four_area, input.angle.data() + 3 * static_cast<size_t>(f));
  }
  input.topology = std::move(topology);
  input.C = std::move(C);
  return input;
}

namespace {

// The build's steps, in order. Each parallel loop writes only its own face's, edge's or vertex's entries.

// A split adds one face, one vertex and two edges. Reserving before the arrays are filled costs no copy,
// and untouched capacity costs no page faults. Lengths and angles taken over from a SignpostInput come with
// this room already.
void reserve_boundary_splits(SignpostTriangulation& tri, const EdgeTopology& topo, int nv, int nf,
                             bool lengths_and_angles) {
  const int ne = static_cast<int>(topo.E.rows());
  const size_t boundary_edges = static_cast<size_t>(boundary_edge_count(topo));
  const size_t halfedges = 3 * (static_cast<size_t>(nf) + boundary_edges);
  const size_t edges = static_cast<size_t>(ne) + 2 * boundary_edges;
  for (auto* v : {&tri.corner_vertex, &tri.twin, &tri.edge}) v->reserve(halfedges);
  tri.phi.reserve(halfedges);
  tri.cot.reserve(halfedges);
  if (lengths_and_angles) {
    tri.angle.reserve(halfedges);
    tri.length.reserve(edges);
  }
  for (auto* v : {&tri.edge_halfedge, &tri.original_edge}) v->reserve(edges);
  tri.edge_vertex.reserve(2 * edges);
  tri.vertex_angle_sum.reserve(static_cast<size_t>(nv) + boundary_edges);
  tri.boundary_vertex.reserve(static_cast<size_t>(nv) + boundary_edges);
}

// Halfedge 3f + k runs from corner k to corner k + 1 of face f and lies on edge FE(f, k + 2).
void set_halfedges(SignpostTriangulation& tri, const EdgeTopology& topo, const Eigen::MatrixXi& F) {
  const int nf = static_cast<int>(F.rows());
  tri.corner_vertex.resize(static_cast<size_t>(3 * nf));
  tri.edge.resize(static_cast<size_t>(3 * nf));
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      tri.corner_vertex[static_cast<size_t>(3 * f + k)] = F(f, k);
      tri.edge[static_cast<size_t>(3 * f + k)] = topo.FE(f, (k + 2) % 3);
    }
}

// Twins and lengths per edge (V's distances unless tri.length holds them already), with the edge's end
// vertices and halfedge; returns the sum of the lengths. Throws TopologyError for a non-manifold or an
// inconsistently oriented edge.
double set_edges(SignpostTriangulation& tri, const EdgeTopology& topo, const Eigen::MatrixXd& V,
                 bool lengths_given) {
  const int ne = static_cast<int>(topo.E.rows());
  tri.twin.assign(tri.corner_vertex.size(), -1);
  tri.edge_halfedge.assign(static_cast<size_t>(ne), -1);
  tri.original_edge.resize(static_cast<size_t>(ne));
  tri.edge_vertex.resize(static_cast<size_t>(2 * ne));
  if (!lengths_given) tri.length.resize(static_cast<size_t>(ne));
  double length_sum = 0.0;
  int bad_edge = ne;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(+ : length_sum) reduction(min : bad_edge)
  for (int e = 0; e < ne; ++e) {
    tri.original_edge[static_cast<size_t>(e)] = e;
    const int i = topo.E(e, 0), j = topo.E(e, 1);
    if (!lengths_given) tri.length[static_cast<size_t>(e)] = input_distance(V, i, j);
    length_sum += tri.length[static_cast<size_t>(e)];
    if (topo.face_count(e) > 2) {
      bad_edge = std::min(bad_edge, e);
      continue;
    }
    const int h0 = 3 * topo.EF(e, 0) + (topo.EK(e, 0) + 1) % 3;
    tri.edge_halfedge[static_cast<size_t>(e)] = h0;
    if (topo.face_count(e) == 2) {
      const int h1 = 3 * topo.EF(e, 1) + (topo.EK(e, 1) + 1) % 3;
      if (tri.tail(h0) == tri.tail(h1)) {
        bad_edge = std::min(bad_edge, e);
        continue;
      }
      tri.twin[static_cast<size_t>(h0)] = h1;
      tri.twin[static_cast<size_t>(h1)] = h0;
      if (tri.tail(h1) < tri.tail(h0)) tri.edge_halfedge[static_cast<size_t>(e)] = h1;
    }
    const int h = tri.edge_halfedge[static_cast<size_t>(e)]; // a boundary edge runs along its one halfedge
    tri.edge_vertex[static_cast<size_t>(2 * e)] = tri.tail(h);
    tri.edge_vertex[static_cast<size_t>(2 * e + 1)] = tri.head(h);
  }
  if (bad_edge < ne) {
    const int e = bad_edge;
    if (topo.face_count(e) > 2)
      throw TopologyError("non-manifold edge " + edge_name(topo.E(e, 0), topo.E(e, 1)) + " is shared by " +
                          std::to_string(topo.face_count(e)) + " faces");
    throw TopologyError("faces " + std::to_string(topo.EF(e, 0)) + " and " + std::to_string(topo.EF(e, 1)) +
                        " are inconsistently oriented across edge " + edge_name(topo.E(e, 0), topo.E(e, 1)));
  }
  return length_sum;
}

// The mollification of Sharp & Crane 2020: one delta added to all lengths so that every triangle
// inequality holds with margin eps; returns delta. Without mollify, a face short of the margin throws
// TopologyError.
double mollify_lengths(SignpostTriangulation& tri, bool mollify, double eps) {
  const int nf = tri.num_faces();
  double delta = 0.0;
  int bad_face = nf;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(max                     \
                                                                                     : delta)                \
    reduction(min                                                                                            \
              : bad_face)
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const double a = tri.halfedge_length(3 * f + k), b = tri.halfedge_length(3 * f + (k + 1) % 3),
                   c = tri.halfedge_length(3 * f + (k + 2) % 3);
      const double need = eps - (b + c - a);
      if (need > 0 && !mollify) bad_face = std::min(bad_face, f);
      delta = std::max(delta, need);
    }
  }
  if (bad_face < nf) {
    double margin = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
      margin = std::min(margin, tri.halfedge_length(3 * bad_face + (k + 1) % 3) +
                                    tri.halfedge_length(3 * bad_face + (k + 2) % 3) -
                                    tri.halfedge_length(3 * bad_face + k));
    throw TopologyError("face " + std::to_string(bad_face) + " is degenerate (triangle inequality margin " +
                        std::to_string(margin) + " below " + std::to_string(eps) +
                        "); enable intrinsic mollification or repair the mesh");
  }
  if (delta > 0)
    for (double& l : tri.length) l += delta;
  return delta;
}

// The fans' CSR holding, per vertex, the halfedges leaving it in increasing index (counting sort by tail);
// each vertex's sweep then overwrites its range in sweep order. (No separate outgoing / swept arrays: 5
// bytes per halfedge less at the peak.)
void bucket_halfedges_by_tail(const SignpostTriangulation& tri, VertexFans& fans) {
  const int nv = tri.num_vertices, nh = static_cast<int>(tri.corner_vertex.size());
  fans.start.assign(static_cast<size_t>(nv) + 1, 0);
  std::vector<int>& start = fans.start;
  for (int h = 0; h < nh; ++h) ++start[static_cast<size_t>(tri.tail(h)) + 1];
  for (int v = 0; v < nv; ++v) start[static_cast<size_t>(v) + 1] += start[static_cast<size_t>(v)];
  fans.entry.resize(static_cast<size_t>(nh));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int h = 0; h < nh; ++h)
    fans.entry[static_cast<size_t>(fill[static_cast<size_t>(tri.tail(h))]++)] = {0.0, h};
}

// Corner angles and cotangents once per face, in parallel (the fan sweeps only add angles up): the input's
// when the lengths are the input's (not mollified), which it then releases.
void set_corner_geometry(SignpostTriangulation& tri, SignpostInput* input) {
  const int nf = tri.num_faces();
  tri.cot.resize(static_cast<size_t>(3 * nf));
  if (input && tri.mollify_delta == 0) {
    tri.angle = std::move(input->angle);
    const Eigen::MatrixXd& C = *input->C;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
    for (int f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) tri.cot[static_cast<size_t>(3 * f + k)] = C(f, (k + 2) % 3);
  } else {
    tri.angle.resize(static_cast<size_t>(3 * nf));
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
    for (int f = 0; f < nf; ++f) tri.update_face_geometry(f);
  }
  if (input) {
    input->C.reset();
    input->angle = {};
  }
}

// Angle sums and signposts: sweeps each vertex's fans counter-clockwise. A fan that ends on the boundary
// starts at its outgoing boundary halfedge, so its angles run from 0 to its total without wrapping. A
// vertex where several open fans meet (a "bowtie", common in scanned meshes) keeps one rotation cell; its
// fans get disjoint angle ranges separated by a gap, so a signpost never points between fans. phi < 0
// marks a halfedge not swept yet. Throws TopologyError for a vertex where a closed fan meets another.
void sweep_vertex_fans(SignpostTriangulation& tri, VertexFans& fans_out) {
  const int nv = tri.num_vertices, nh = static_cast<int>(tri.corner_vertex.size());
  const std::vector<int>& start = fans_out.start;
  tri.phi.assign(static_cast<size_t>(nh), -1.0);
  tri.vertex_angle_sum.assign(static_cast<size_t>(nv), 0.0);
  tri.boundary_vertex.assign(static_cast<size_t>(nv), 0);
  const std::vector<double>& corner = tri.angle;
  // Each vertex's sweeps touch only the halfedges leaving it, so vertices run in parallel. Open fans come
  // first, from their boundary halfedge, then the closed fan; within each, in increasing halfedge index.
  int bad_vertex = nv;
#pragma omp parallel num_threads(loop_thread_count()) reduction(min : bad_vertex)
  {
    std::vector<int> outgoing;
    // One step of a sweep: halfedge h becomes fan entry `slot` at `angle`, its corner is added, and the next
    // halfedge leaving the same vertex counter-clockwise is returned (-1 past a boundary halfedge).
    auto step = [&](int h, int slot, double& angle) {
      tri.phi[static_cast<size_t>(h)] = angle;
      fans_out.entry[static_cast<size_t>(slot)] = {angle, h};
      angle += corner[static_cast<size_t>(h)];
      return tri.twin[static_cast<size_t>(prev_halfedge(h))];
    };
#pragma omp for schedule(dynamic, 1024)
    for (int v = 0; v < nv; ++v) {
      const int first = start[static_cast<size_t>(v)], last = start[static_cast<size_t>(v) + 1];
      // An interior vertex (most of them): its one closed fan visits each halfedge leaving it once, so the
      // sweep is a loop of known length from its lowest halfedge (where the general sweep below starts too).
      // Each step waits for the load of the next twin; with a known trip count the processor runs ahead into
      // the next vertices meanwhile, where a loop that ends on the loaded value stalls on it (beetle:
      // signpost input and build 0.95-0.975 of their time). Back at the first halfedge before the end, or not
      // at it after, the vertex has several closed fans: non-manifold, reported below.
      bool interior = last > first;
      for (int k = first; k < last; ++k)
        interior &= tri.twin[static_cast<size_t>(fans_out.entry[static_cast<size_t>(k)].halfedge)] >= 0;
      if (interior) {
        const int h0 = fans_out.entry[static_cast<size_t>(first)].halfedge;
        int h = h0;
        double angle = 0.0;
        bool back_early = false;
        for (int k = first; k < last; ++k) {
          h = step(h, k, angle);
          back_early |= h == h0 && k + 1 < last;
        }
        tri.vertex_angle_sum[static_cast<size_t>(v)] = angle;
        if (back_early || h != h0) bad_vertex = std::min(bad_vertex, v);
        continue;
      }
      outgoing.clear();
      for (int k = first; k < last; ++k) outgoing.push_back(fans_out.entry[static_cast<size_t>(k)].halfedge);
      int fans = 0, fill = first;
      bool closed = false;
      double angle = 0.0;
      auto sweep = [&](int h0) {
        if (fans > 0) angle += 1.0; // gap between fans
        int h = h0;
        while (true) {
          const int t = step(h, fill++, angle);
          if (t < 0) break;
          if (t == h0) {
            closed = true;
            break;
          }
          h = t;
        }
        ++fans;
      };
      for (int h : outgoing)
        if (tri.twin[static_cast<size_t>(h)] < 0) {
          tri.boundary_vertex[static_cast<size_t>(v)] = 1;
          sweep(h);
        }
      for (int h : outgoing)
        if (tri.phi[static_cast<size_t>(h)] < 0) sweep(h);
      tri.vertex_angle_sum[static_cast<size_t>(v)] = angle;
      if (fans > 1 && closed) bad_vertex = std::min(bad_vertex, v);
    }
  }
  if (bad_vertex < nv) {
    int fans = 0;
    for (int h = 0; h < nh; ++h) fans += tri.tail(h) == bad_vertex && tri.twin[static_cast<size_t>(h)] < 0;
    throw TopologyError("non-manifold vertex " + std::to_string(bad_vertex) + ": a closed fan of faces and " +
                        std::to_string(std::max(fans, 1)) +
                        " more fans meet there (two surfaces touching at a point)");
  }
}

} // namespace

SignpostTriangulation build_signpost_triangulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                   bool mollify, double mollify_epsilon, VertexFans& fans_out,
                                                   bool room_for_boundary_splits, SignpostInput* input) {
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(F.rows());
  if (!input) check_signpost_input(V, F); // signpost_input checked them
  // Released once twins and lengths are set (peak memory).
  std::shared_ptr<const EdgeTopology> topology =
      input ? std::move(input->topology) : std::make_shared<const EdgeTopology>(edge_topology(F, nv));
  const int ne = static_cast<int>(topology->E.rows());
  SignpostTriangulation tri;
  tri.num_vertices = nv;
  tri.num_input_vertices = nv;
  if (room_for_boundary_splits) reserve_boundary_splits(tri, *topology, nv, nf, !input);
  set_halfedges(tri, *topology, F);
  if (input) tri.length = std::move(input->length);
  const double length_sum = set_edges(tri, *topology, V, input != nullptr);
  topology.reset();
  tri.mollify_delta = mollify_lengths(tri, mollify, mollify_epsilon * length_sum / std::max(ne, 1));
  bucket_halfedges_by_tail(tri, fans_out);
  set_corner_geometry(tri, input);
  sweep_vertex_fans(tri, fans_out);
  return tri;
}

namespace {

// Halfedges, edges and lengths from given twins; returns the sum of the lengths. Edge e runs from its
// smaller end E(e, 0) to E(e, 1) along edge_halfedge[e].
double set_glued_edges(SignpostTriangulation& tri, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       const std::vector<int>& twin) {
  const int nh = static_cast<int>(3 * F.rows());
  if (static_cast<int>(twin.size()) != nh)
    throw TopologyError("glued triangulation: " + std::to_string(twin.size()) + " twins for " +
                        std::to_string(nh) + " halfedges");
  tri.corner_vertex.resize(static_cast<size_t>(nh));
  for (int h = 0; h < nh; ++h) tri.corner_vertex[static_cast<size_t>(h)] = F(h / 3, h % 3);
  tri.twin = twin;
  tri.edge.assign(static_cast<size_t>(nh), -1);
  double length_sum = 0.0;
  for (int h = 0; h < nh; ++h) {
    const int t = twin[static_cast<size_t>(h)];
    if (t >= nh || (t >= 0 && (twin[static_cast<size_t>(t)] != h || tri.tail(t) != tri.head(h) ||
                               tri.head(t) != tri.tail(h))))
      throw TopologyError("glued triangulation: halfedge " + std::to_string(h) + " " +
                          edge_name(tri.tail(h), tri.head(h)) + " is not glued to a halfedge running back");
    if (t >= 0 && t < h) continue; // numbered from its lower halfedge
    const int e = static_cast<int>(tri.length.size());
    tri.edge[static_cast<size_t>(h)] = e;
    if (t >= 0) tri.edge[static_cast<size_t>(t)] = e;
    const int along = t >= 0 && tri.tail(t) < tri.tail(h) ? t : h;
    tri.edge_halfedge.push_back(along);
    tri.edge_vertex.push_back(tri.tail(along));
    tri.edge_vertex.push_back(tri.head(along));
    tri.original_edge.push_back(e);
    tri.length.push_back(input_distance(V, tri.tail(h), tri.head(h)));
    length_sum += tri.length.back();
  }
  return length_sum;
}

} // namespace

SignpostTriangulation build_glued_signpost_triangulation(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                                         const std::vector<int>& twin, bool mollify,
                                                         double mollify_epsilon, VertexFans& fans) {
  check_signpost_input(V, F);
  SignpostTriangulation tri;
  tri.num_vertices = tri.num_input_vertices = static_cast<int>(V.rows());
  const double length_sum = set_glued_edges(tri, V, F, twin);
  tri.mollify_delta =
      mollify_lengths(tri, mollify, mollify_epsilon * length_sum / std::max(tri.num_edges(), 1));
  bucket_halfedges_by_tail(tri, fans);
  set_corner_geometry(tri, nullptr);
  sweep_vertex_fans(tri, fans);
  return tri;
}

InputTriangulation input_triangulation(const SignpostTriangulation& unflipped) {
  InputTriangulation input;
  const int nh = 3 * unflipped.num_faces();
  input.halfedge.resize(static_cast<size_t>(nh));
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int h = 0; h < nh; ++h)
    input.halfedge[static_cast<size_t>(h)] = {unflipped.tail(h), unflipped.twin[static_cast<size_t>(h)],
                                              unflipped.halfedge_length(h),
                                              unflipped.angle[static_cast<size_t>(h)]};
  input.edge_halfedge = unflipped.edge_halfedge;
  return input;
}

namespace {

// edge_halfedge of the edge of slot s: of an edge's two halfedges, the one with the lower tail vertex
// (E(e,0) <= E(e,1)).
void refresh_edge_halfedge(SignpostTriangulation& tri, int s) {
  const int x = tri.twin[static_cast<size_t>(s)];
  const int edge_id = tri.edge[static_cast<size_t>(s)];
  int best = s;
  if (x >= 0 && (tri.tail(x) < tri.tail(s) || (tri.tail(x) == tri.tail(s) && x < s))) best = x;
  tri.edge_halfedge[static_cast<size_t>(edge_id)] = best;
}

} // namespace

bool flip_edge(SignpostTriangulation& tri, int e) {
  auto& twin = tri.twin;
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  const int t = twin[static_cast<size_t>(h)];
  if (t < 0) return false;
  const int f0 = h / 3, f1 = t / 3;
  if (f0 == f1) return false;
  // Before: f0 = (a, b, c) with h = a->b, h1 = b->c, h2 = c->a; f1 = (b, a, d) with t = b->a, t1 = a->d, t2 =
  // d->b.
  const int h1 = next_halfedge(h), h2 = prev_halfedge(h), t1 = next_halfedge(t), t2 = prev_halfedge(t);
  const int a = tri.tail(h), b = tri.tail(t), c = tri.tail(h2), d = tri.tail(t2);
  const int e_bc = tri.edge[static_cast<size_t>(h1)], e_ca = tri.edge[static_cast<size_t>(h2)];
  const int e_ad = tri.edge[static_cast<size_t>(t1)], e_db = tri.edge[static_cast<size_t>(t2)];
  if (e_bc == e || e_ca == e || e_ad == e || e_db == e) return false;
  // Planar layout of the two triangles: a at the origin, b on the +x axis, c above, d below.
  const double l_ab = tri.length[static_cast<size_t>(e)];
  const double l_bc = tri.halfedge_length(h1), l_ca = tri.halfedge_length(h2);
  const double l_ad = tri.halfedge_length(t1), l_db = tri.halfedge_length(t2);
  const double cx = (l_ca * l_ca - l_bc * l_bc + l_ab * l_ab) / (2 * l_ab);
  const double cy = std::sqrt(std::max(l_ca * l_ca - cx * cx, 0.0));
  const double dx = (l_ad * l_ad - l_db * l_db + l_ab * l_ab) / (2 * l_ab);
  const double dy = -std::sqrt(std::max(l_ad * l_ad - dx * dx, 0.0));
  // The quad is convex at a and b (the new diagonal stays inside it) iff segment cd crosses the x axis
  // strictly between a and b: the same test as "both quad angles at a and b below pi", without angles.
  if (!(cy > 0.0 && dy < 0.0)) return false;
  const double x_cross = cx + (dx - cx) * cy / (cy - dy);
  if (!(x_cross > 0.0 && x_cross < l_ab)) return false;
  const double l_cd = std::sqrt((cx - dx) * (cx - dx) + (cy - dy) * (cy - dy)); // mesh-scale: no hypot needed

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
  tri.edge_vertex[static_cast<size_t>(2 * e)] = std::min(c, d);
  tri.edge_vertex[static_cast<size_t>(2 * e + 1)] = std::max(c, d);
  for (int s : {n_ca, n_ad, n_db, n_bc}) refresh_edge_halfedge(tri, s);
  // Signposts of the new diagonal: rotate from the neighbouring halfedge by the new corner angle.
  auto wrap = [&](int v, double angle) {
    const double theta = tri.vertex_angle_sum[static_cast<size_t>(v)];
    if (tri.boundary_vertex[static_cast<size_t>(v)]) return std::min(angle, theta);
    return angle >= theta ? angle - theta : angle;
  };
  // Corner angles: those at a and b are sums of the old ones and the diagonal splits those at c and d, so
  // only f0's new angles at c and d need an atan2 (from f0's area, as in update_face_geometry): two per flip,
  // not six.
  const double angle_a = tri.angle[static_cast<size_t>(h)] + tri.angle[static_cast<size_t>(t1)];
  const double angle_b = tri.angle[static_cast<size_t>(h1)] + tri.angle[static_cast<size_t>(t)];
  const double angle_c = tri.angle[static_cast<size_t>(h2)], angle_d = tri.angle[static_cast<size_t>(t2)];
  // f0 = (c, a, d) with sides l_ca, l_ad, l_cd: its cotangents, and its angles at c and d from the same area
  // and law-of-cosines terms.
  const double l0[3] = {l_ca, l_ad, l_cd};
  double terms0[3];
  const double four_area = write_face_cotangents(tri, f0, l0, terms0);
  const double c0 = upper_half_angle(four_area, terms0[1]);
  const double d0 = upper_half_angle(four_area, terms0[0]);
  const double slots[6] = {
      c0, angle_a, d0, std::max(angle_d - d0, 0.0), angle_b, std::max(angle_c - c0, 0.0)};
  for (int k = 0; k < 3; ++k) {
    tri.angle[static_cast<size_t>(3 * f0 + k)] = slots[k];
    tri.angle[static_cast<size_t>(3 * f1 + k)] = slots[3 + k];
  }
  tri.update_face_cotangents(f1);
  tri.phi[static_cast<size_t>(n_cd)] = wrap(c, phi_ca + tri.angle[static_cast<size_t>(n_ca)]);
  tri.phi[static_cast<size_t>(n_dc)] = wrap(d, phi_db + tri.angle[static_cast<size_t>(n_db)]);
  tri.original_edge[static_cast<size_t>(e)] = -1;
  return true;
}

namespace {

bool is_non_delaunay(const SignpostTriangulation& tri, int e, double tolerance) {
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  const int t = tri.twin[static_cast<size_t>(h)];
  return t >= 0 && tri.cot[static_cast<size_t>(h)] + tri.cot[static_cast<size_t>(t)] < -tolerance;
}

// The interior edges failing the Delaunay test, in increasing order (parallel scan).
std::vector<int> non_delaunay_edges(const SignpostTriangulation& tri, double tolerance) {
  const int ne = tri.num_edges();
  std::vector<char> failing(static_cast<size_t>(ne));
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int e = 0; e < ne; ++e) failing[static_cast<size_t>(e)] = is_non_delaunay(tri, e, tolerance);
  std::vector<int> edges;
  for (int e = 0; e < ne; ++e)
    if (failing[static_cast<size_t>(e)]) edges.push_back(e);
  return edges;
}

} // namespace

int count_non_delaunay(const SignpostTriangulation& tri, double tolerance) {
  return static_cast<int>(non_delaunay_edges(tri, tolerance).size());
}

FlipStats flip_to_delaunay(SignpostTriangulation& tri, double tolerance, const std::vector<int>* seeds) {
  FlipStats stats;
  // Only edges that fail now need a look: any other edge can only start failing when a flip changes one of
  // its two faces, and then it is pushed.
  std::vector<int> stack;
  if (seeds) {
    for (int e : *seeds)
      if (is_non_delaunay(tri, e, tolerance)) stack.push_back(e);
    std::sort(stack.begin(), stack.end());
    stack.erase(std::unique(stack.begin(), stack.end()), stack.end());
  } else {
    stack = non_delaunay_edges(tri, tolerance);
  }
  stats.non_delaunay_before = static_cast<int>(stack.size());
  std::reverse(stack.begin(), stack.end()); // pop in increasing edge order, as a full sweep would
  const int ne = tri.num_edges();
  std::vector<char> queued(static_cast<size_t>(ne), 0);
  for (int e : stack) queued[static_cast<size_t>(e)] = 1;
  // Each flip strictly lowers the Dirichlet energy of the piecewise-linear interpolant (Rippa, Bobenko &
  // Springborn), so the loop ends; the cap only guards against a numerical cycle.
  const long max_flips = 1000L * ne + 1000000L;
  std::vector<int> stuck;
  while (!stack.empty()) {
    const int e = stack.back();
    stack.pop_back();
    queued[static_cast<size_t>(e)] = 0;
    if (!is_non_delaunay(tri, e, tolerance)) continue;
    if (!flip_edge(tri, e)) {
      stuck.push_back(e); // re-checked at the end: a later neighbouring flip may have fixed it
      continue;
    }
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
  // Every other edge was last checked Delaunay after its last change; only unflippable ones can fail.
  std::sort(stuck.begin(), stuck.end());
  stuck.erase(std::unique(stuck.begin(), stuck.end()), stuck.end());
  for (int e : stuck) stats.non_delaunay_after += is_non_delaunay(tri, e, tolerance);
  return stats;
}

int count_obtuse_boundary_edges(const SignpostTriangulation& tri, double tolerance) {
  int count = 0;
  for (int e = 0; e < tri.num_edges(); ++e) {
    const int h = tri.edge_halfedge[static_cast<size_t>(e)];
    if (tri.twin[static_cast<size_t>(h)] < 0 && tri.cot[static_cast<size_t>(h)] < -tolerance) ++count;
  }
  return count;
}

namespace {

// Where a point at parameter t along intrinsic boundary halfedge h lies on the input: the input boundary
// halfedge and its parameter. Intrinsic boundary edges are never flipped, so h is a piece of one input
// boundary halfedge, from tail point to head point.
std::pair<int, double> locate_on_input_boundary(const SignpostTriangulation& tri,
                                                const InputTriangulation& input, int h, double t) {
  auto position = [&](int v, int hb_hint) -> std::pair<int, double> {
    if (v >= tri.num_input_vertices) {
      const size_t q = static_cast<size_t>(v - tri.num_input_vertices);
      return {tri.inserted_halfedge[q], tri.inserted_t[q]};
    }
    return {hb_hint, input.tail(hb_hint) == v ? 0.0 : 1.0};
  };
  const int a = tri.tail(h), b = tri.head(h);
  // The input boundary halfedge carrying h: known from an inserted end, else the input edge a -> b.
  int hb = -1;
  if (a >= tri.num_input_vertices)
    hb = tri.inserted_halfedge[static_cast<size_t>(a - tri.num_input_vertices)];
  else if (b >= tri.num_input_vertices)
    hb = tri.inserted_halfedge[static_cast<size_t>(b - tri.num_input_vertices)];
  else {
    const int e = tri.original_edge[static_cast<size_t>(tri.edge[static_cast<size_t>(h)])];
    hb = input.edge_halfedge[static_cast<size_t>(e)];
  }
  const double ta = position(a, hb).second, tb = position(b, hb).second;
  return {hb, ta + t * (tb - ta)};
}

// Splits boundary edge e of face (i, j, k) at parameter t from i: faces (i, p, k) and (p, j, k).
void split_boundary_edge(SignpostTriangulation& tri, const InputTriangulation& input, int e, double t) {
  const int h = tri.edge_halfedge[static_cast<size_t>(e)];
  const int f = h / 3, g = tri.num_faces();
  const int h1 = next_halfedge(h), h2 = prev_halfedge(h);
  const int i = tri.tail(h), j = tri.head(h), k = tri.tail(h2);
  const int e_jk = tri.edge[static_cast<size_t>(h1)], e_ki = tri.edge[static_cast<size_t>(h2)];
  const double l_ij = tri.length[static_cast<size_t>(e)], l_jk = tri.halfedge_length(h1),
               l_ki = tri.halfedge_length(h2);
  const double kx = (l_ki * l_ki - l_jk * l_jk + l_ij * l_ij) / (2 * l_ij);
  const double ky = std::sqrt(std::max(l_ki * l_ki - kx * kx, 0.0));
  const double l_pk = std::hypot(kx - t * l_ij, ky);
  const auto [hb, tb] = locate_on_input_boundary(tri, input, h, t);

  const int p = tri.num_vertices++;
  tri.inserted_halfedge.push_back(hb);
  tri.inserted_t.push_back(tb);
  tri.vertex_angle_sum.push_back(kPi);
  tri.boundary_vertex.push_back(1);
  const int e_pj = tri.num_edges(), e_pk = e_pj + 1;
  tri.length.push_back((1 - t) * l_ij);
  tri.length.push_back(l_pk);
  tri.original_edge.push_back(-1);
  tri.original_edge.push_back(-1);
  tri.edge_halfedge.resize(static_cast<size_t>(e_pk + 1));
  // The tails of the halfedges chosen below: i -> p (boundary), p -> j (boundary), k -> p (k < p, interior).
  tri.edge_vertex[static_cast<size_t>(2 * e + 1)] = p;
  for (int x : {p, j, k, p}) tri.edge_vertex.push_back(x);
  tri.length[static_cast<size_t>(e)] = t * l_ij;
  tri.original_edge[static_cast<size_t>(e)] = -1;
  for (auto* v : {&tri.corner_vertex, &tri.twin, &tri.edge}) v->resize(static_cast<size_t>(3 * g + 3));
  for (auto* v : {&tri.phi, &tri.angle, &tri.cot}) v->resize(static_cast<size_t>(3 * g + 3));

  const int x_jk = tri.twin[static_cast<size_t>(h1)], x_ki = tri.twin[static_cast<size_t>(h2)];
  const double phi_ij = tri.phi[static_cast<size_t>(h)], phi_ki = tri.phi[static_cast<size_t>(h2)];
  const double phi_jk = tri.phi[static_cast<size_t>(h1)];
  const int s_ip = 3 * f, s_pk = 3 * f + 1, s_ki = 3 * f + 2, s_pj = 3 * g, s_jk = 3 * g + 1,
            s_kp = 3 * g + 2;
  auto moved = [&](int x) { return x == h1 ? s_jk : x == h2 ? s_ki : x; };
  auto set = [&](int slot, int vertex, int edge_id, int twin_slot, double phi) {
    tri.corner_vertex[static_cast<size_t>(slot)] = vertex;
    tri.edge[static_cast<size_t>(slot)] = edge_id;
    tri.twin[static_cast<size_t>(slot)] = twin_slot;
    tri.phi[static_cast<size_t>(slot)] = phi;
    if (twin_slot >= 0) tri.twin[static_cast<size_t>(twin_slot)] = slot;
  };
  set(s_ip, i, e, -1, phi_ij);
  set(s_ki, k, e_ki, moved(x_ki), phi_ki);
  set(s_jk, j, e_jk, moved(x_jk), phi_jk);
  set(s_pj, p, e_pj, -1, 0.0);
  set(s_pk, p, e_pk, -1, 0.0);
  set(s_kp, k, e_pk, s_pk, 0.0);
  tri.edge_halfedge[static_cast<size_t>(e)] = s_ip;
  tri.edge_halfedge[static_cast<size_t>(e_pj)] = s_pj;
  tri.edge_halfedge[static_cast<size_t>(e_pk)] = k < p ? s_kp : s_pk;
  for (int s : {s_ki, s_jk}) {
    const int x = tri.twin[static_cast<size_t>(s)];
    int best = s;
    if (x >= 0 && (tri.tail(x) < tri.tail(s) || (tri.tail(x) == tri.tail(s) && x < s))) best = x;
    tri.edge_halfedge[static_cast<size_t>(tri.edge[static_cast<size_t>(s)])] = best;
  }
  tri.update_face_geometry(f);
  tri.update_face_geometry(g);
  // Signposts at p: 0 along the boundary towards j, then counter-clockwise; at k: from k -> i by the new
  // corner.
  tri.phi[static_cast<size_t>(s_pk)] = tri.angle[static_cast<size_t>(s_pj)];
  tri.vertex_angle_sum[static_cast<size_t>(p)] =
      tri.angle[static_cast<size_t>(s_pj)] + tri.angle[static_cast<size_t>(s_pk)];
  double phi_kp = phi_ki + tri.angle[static_cast<size_t>(s_ki)];
  const double theta_k = tri.vertex_angle_sum[static_cast<size_t>(k)];
  if (tri.boundary_vertex[static_cast<size_t>(k)])
    phi_kp = std::min(phi_kp, theta_k);
  else if (phi_kp >= theta_k)
    phi_kp -= theta_k;
  tri.phi[static_cast<size_t>(s_kp)] = phi_kp;
}

} // namespace

RefineStats refine_obtuse_boundary(SignpostTriangulation& tri, const InputTriangulation& input,
                                   double tolerance, int max_insertions) {
  RefineStats stats;
  // Boundary edges are never flipped and a split keeps e on the boundary and adds e_pj, so this list
  // stays complete; each round looks at it instead of at every edge.
  std::vector<int> boundary;
  for (int e = 0; e < tri.num_edges(); ++e)
    if (tri.twin[static_cast<size_t>(tri.edge_halfedge[static_cast<size_t>(e)])] < 0) boundary.push_back(e);
  auto obtuse = [&](int e) {
    return tri.cot[static_cast<size_t>(tri.edge_halfedge[static_cast<size_t>(e)])] < -tolerance;
  };
  stats.obtuse_before = static_cast<int>(std::count_if(boundary.begin(), boundary.end(), obtuse));
  while (stats.inserted < max_insertions) {
    std::vector<int> candidates;
    for (int e : boundary)
      if (obtuse(e)) candidates.push_back(e);
    if (candidates.empty()) break;
    ++stats.rounds;
    std::vector<int> touched; // the edges of the faces the splits changed: the only ones that may fail now
    for (int e : candidates) {
      if (stats.inserted >= max_insertions) break;
      if (!obtuse(e)) continue; // fixed by an earlier split of this round
      const int h = tri.edge_halfedge[static_cast<size_t>(e)];
      // Foot of the altitude from the obtuse corner: inside the edge, since the other two angles are acute.
      const double l_ij = tri.halfedge_length(h), l_jk = tri.halfedge_length(next_halfedge(h)),
                   l_ki = tri.halfedge_length(prev_halfedge(h));
      const double t = std::clamp((l_ki * l_ki - l_jk * l_jk + l_ij * l_ij) / (2 * l_ij * l_ij), 0.05, 0.95);
      for (int x :
           {tri.edge[static_cast<size_t>(next_halfedge(h))], tri.edge[static_cast<size_t>(prev_halfedge(h))]})
        touched.push_back(x);
      split_boundary_edge(tri, input, e, t);
      boundary.push_back(tri.num_edges() - 2); // e_pj
      touched.push_back(tri.num_edges() - 1);  // e_pk
      ++stats.inserted;
    }
    stats.flips += flip_to_delaunay(tri, tolerance, &touched).flips;
  }
  stats.obtuse_after = static_cast<int>(std::count_if(boundary.begin(), boundary.end(), obtuse));
  return stats;
}

} // namespace iarap::detail
