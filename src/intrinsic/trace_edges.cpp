#include "trace_edges.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"

#include "../core/parallel_chunks.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace iarap::detail {

namespace {

struct Vec2 {
  double x, y;
  Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  Vec2 operator*(double s) const { return {x * s, y * s}; }
};
double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
double norm(Vec2 a) {
  return std::sqrt(a.x * a.x + a.y * a.y);
} // mesh-scale values: no hypot needed

// Position of the third corner of the face left of the directed segment pa -> pb, whose length is l_ab
// (|pb - pa| up to rounding: dividing by l_ab keeps a square root and a division off the walk's critical
// path).
Vec2 third_corner(Vec2 pa, Vec2 pb, double l_ab, double l_ac, double l_bc) {
  const Vec2 ex = (pb - pa) * (1.0 / l_ab);
  const Vec2 ey{-ex.y, ex.x};
  const double x = (l_ac * l_ac - l_bc * l_bc + l_ab * l_ab) / (2 * l_ab);
  const double y = std::sqrt(std::max(l_ac * l_ac - x * x, 0.0));
  return pa + ex * x + ey * y;
}

[[noreturn]] void trace_failure(int e, int i, int j, const std::string& why) {
  throw SolverError("tracing intrinsic edge " + std::to_string(e) + " (" + std::to_string(i) + " -> " +
                    std::to_string(j) + ") over the input mesh failed: " + why);
}

// Where an intrinsic vertex lies on the input: an input vertex (c = -1) or a point of input boundary
// halfedge (a -> c) at parameter t.
struct InputPoint {
  int a, c;
  double t;
  int halfedge; // the input boundary halfedge of an inserted point, else -1
};

InputPoint input_point(const EdgesToTrace& flipped, const InputTriangulation& input, int v) {
  if (v < flipped.num_input_vertices) return {v, -1, 0.0, -1};
  const size_t q = static_cast<size_t>(v - flipped.num_input_vertices);
  const int hb = flipped.inserted_halfedge[q];
  return {input.tail(hb), input.head(hb), flipped.inserted_t[q], hb};
}

// The 2D position of `target` if it lies on the face with corners (va, pa), (vb, pb), (vc, pc).
bool target_in_face(const InputPoint& target, const int (&v)[3], const Vec2 (&pos)[3], Vec2& where) {
  int ia = -1, ic = -1;
  for (int q = 0; q < 3; ++q) {
    if (v[q] == target.a) ia = q;
    if (v[q] == target.c) ic = q;
  }
  if (ia < 0) return false;
  if (target.c < 0) {
    where = pos[ia];
    return true;
  }
  if (ic < 0) return false;
  where = pos[ia] * (1 - target.t) + pos[ic] * target.t;
  return true;
}

// Appends the points of flipped edge number `job` to `out`.
void trace_one(const InputTriangulation& input, const VertexFans& fans, const EdgesToTrace& flipped, int job,
               std::vector<TracePoint>& out) {
  const size_t k = static_cast<size_t>(job);
  const int e = flipped.edge[k], i = flipped.tail[k], j = flipped.head[k];
  const double length = flipped.length[k], phi = flipped.phi[k];
  const double tol = 1e-7 * length; // snapping distance at the end; tracing errors are ~1e-14 * length
  const InputPoint start = input_point(flipped, input, i), target = input_point(flipped, input, j);

  // State of the walk: the ray p + r dir is inside the face left of input halfedge `entry`, whose tail and
  // head sit at pa and pb. From an input vertex, the first face is the fan corner holding phi; the ray
  // leaves it through the opposite halfedge.
  Vec2 dir, p{0, 0}, pa, pb;
  int entry = -1;
  double remaining = length;
  // The ray leaves the current face through input halfedge x (tail at q0, head at q1): record the crossing
  // and enter the face across x, whose halfedge twin(x) runs head(x) -> tail(x), so its tail sits at q1.
  auto cross_halfedge = [&](int x, Vec2 q0, Vec2 q1) {
    const Vec2 edge_vec = q1 - q0;
    const double denom = cross(dir, edge_vec);
    const double r = cross(q0 - p, edge_vec) / denom;
    const double s = std::clamp(cross(q0 - p, dir) / denom, 0.0, 1.0);
    if (!(r < remaining - tol))
      trace_failure(e, i, j,
                    "the line ends inside input face " + std::to_string(x / 3) + " away from the end vertex");
    const int tx = input[x].twin;
    if (tx < 0)
      trace_failure(e, i, j, "the line leaves the surface through boundary halfedge " + std::to_string(x));
    out.push_back({input.tail(x), input.head(x), tx / 3, s});
    p = p + dir * r;
    remaining -= r;
    entry = tx;
    pa = q1;
    pb = q0;
  };
  if (start.c < 0) {
    const int first = fans.start[static_cast<size_t>(i)], last = fans.start[static_cast<size_t>(i + 1)];
    const auto fan = fans.entry.begin();
    const auto above =
        std::upper_bound(fan + first, fan + last, phi, [](double angle, const VertexFans::Entry& fan_entry) {
          return angle < fan_entry.phi;
        });
    const VertexFans::Entry& corner =
        fans.entry[static_cast<size_t>(std::max(static_cast<int>(above - fan) - 1, first))];
    const int hin = corner.halfedge;
    const double alpha = std::clamp(phi - corner.phi, 0.0, input[hin].angle);
    const int u = input.head(hin), w = input.tail(prev_halfedge(hin));
    const double l_iu = input[hin].length;
    const Vec2 pu{l_iu, 0};
    const Vec2 pw =
        third_corner(p, pu, l_iu, input[prev_halfedge(hin)].length, input[next_halfedge(hin)].length);
    dir = {std::cos(alpha), std::sin(alpha)};
    out.push_back({i, -1, hin / 3, 0.0});
    Vec2 goal;
    if (target_in_face(target, {i, u, w}, {p, pu, pw}, goal) && norm(dir * length - goal) <= tol) {
      out.push_back({target.a, target.c, -1, target.t});
      return;
    }
    // Leave through u -> w into the next face.
    cross_halfedge(next_halfedge(hin), pu, pw);
  } else {
    // An inserted point on input boundary halfedge a -> c: phi = 0 points towards c, the face is on the left.
    entry = start.halfedge;
    const double l_ac = input[entry].length;
    pa = {-start.t * l_ac, 0};
    pb = {(1 - start.t) * l_ac, 0};
    dir = {std::cos(phi), std::sin(phi)};
    out.push_back({start.a, start.c, entry / 3, start.t});
  }

  const int max_steps = 4 * input.num_faces() + 16;
  for (int step = 0; step < max_steps; ++step) {
    // In the face left of `entry` (tail at pa, head at pb); its third corner is c.
    const int va = input.tail(entry), vb = input.head(entry), c = input.tail(prev_halfedge(entry));
    const Vec2 pc = third_corner(pa, pb, input[entry].length, input[prev_halfedge(entry)].length,
                                 input[next_halfedge(entry)].length);
    Vec2 goal;
    if (target_in_face(target, {va, vb, c}, {pa, pb, pc}, goal) && norm(p + dir * remaining - goal) <= tol) {
      out.push_back({target.a, target.c, -1, target.t});
      return;
    }
    // pa is left of the ray and pb right of it: the ray leaves through b -> c when c is on its left.
    int x;
    Vec2 q0, q1;
    if (cross(dir, pc - p) > 0) {
      x = next_halfedge(entry);
      q0 = pb;
      q1 = pc;
    } else {
      x = prev_halfedge(entry);
      q0 = pc;
      q1 = pa;
    }
    cross_halfedge(x, q0, q1);
  }
  trace_failure(e, i, j, "more than " + std::to_string(max_steps) + " crossings");
}

} // namespace

EdgesToTrace flipped_edges(const SignpostTriangulation& intrinsic) {
  EdgesToTrace flipped;
  flipped.num_input_vertices = intrinsic.num_input_vertices;
  flipped.inserted_halfedge = intrinsic.inserted_halfedge;
  flipped.inserted_t = intrinsic.inserted_t;
  const size_t count = static_cast<size_t>(std::count_if(
      intrinsic.original_edge.begin(), intrinsic.original_edge.end(), [](int o) { return o < 0; }));
  for (auto* v : {&flipped.edge, &flipped.tail, &flipped.head}) v->reserve(count);
  for (auto* v : {&flipped.phi, &flipped.length}) v->reserve(count);
  for (int e = 0; e < intrinsic.num_edges(); ++e) {
    if (intrinsic.original_edge[static_cast<size_t>(e)] >= 0) continue;
    const int h = intrinsic.edge_halfedge[static_cast<size_t>(e)];
    flipped.edge.push_back(e);
    flipped.tail.push_back(intrinsic.tail(h));
    flipped.head.push_back(intrinsic.head(h));
    flipped.phi.push_back(intrinsic.phi[static_cast<size_t>(h)]);
    flipped.length.push_back(intrinsic.length[static_cast<size_t>(e)]);
  }
  return flipped;
}

CompactTraces trace_edges(const InputTriangulation& input, const VertexFans& fans,
                          const EdgesToTrace& flipped, const std::vector<int>& original_edge) {
  const int ne = static_cast<int>(original_edge.size());
  const int nk = static_cast<int>(flipped.edge.size());
  // The flipped edges are traced into per-thread buffers, then concatenated in edge order.
  std::vector<int> count(static_cast<size_t>(nk)), owner(static_cast<size_t>(nk)),
      offset(static_cast<size_t>(nk));
  std::vector<std::vector<TracePoint>> buffers(static_cast<size_t>(chunk_workers()));
  // Room for 8 points per edge (a few on a mesh near Delaunay): reserved capacity that stays unused costs
  // no page faults, and growing by copies does.
  for (auto& buffer : buffers)
    buffer.reserve(8 * static_cast<size_t>(nk / static_cast<int>(buffers.size()) + 1));
  std::string error;
  parallel_chunks(nk, 256, [&](int begin, int end, int worker) {
    auto& buffer = buffers[static_cast<size_t>(worker)];
    for (int k = begin; k < end; ++k) {
      const size_t before = buffer.size();
      try {
        trace_one(input, fans, flipped, k, buffer);
      } catch (const std::exception& ex) {
#pragma omp critical(iarap_trace_error)
        if (error.empty()) error = ex.what();
        buffer.resize(before);
      }
      count[static_cast<size_t>(k)] = static_cast<int>(buffer.size() - before);
      owner[static_cast<size_t>(k)] = worker;
      offset[static_cast<size_t>(k)] = static_cast<int>(before);
    }
  });
  if (!error.empty()) throw SolverError(error);

  CompactTraces compact;
  compact.start.resize(static_cast<size_t>(nk) + 1);
  compact.start[0] = 0;
  for (int k = 0; k < nk; ++k)
    compact.start[static_cast<size_t>(k) + 1] =
        compact.start[static_cast<size_t>(k)] + count[static_cast<size_t>(k)];
  // One thread took the chunks in order (one thread allowed, or the other busy throughout): its buffer is
  // the result.
  bool in_order = true;
  for (int k = 0; k < nk && in_order; ++k)
    in_order = owner[static_cast<size_t>(k)] == 0 &&
               offset[static_cast<size_t>(k)] == compact.start[static_cast<size_t>(k)];
  if (in_order && nk > 0) {
    compact.points = std::move(buffers[0]);
  } else {
    compact.points.resize(static_cast<size_t>(compact.start.back()));
    parallel_chunks(nk, 1024, [&](int begin, int end, int) {
      for (int k = begin; k < end; ++k) {
        const TracePoint* from = buffers[static_cast<size_t>(owner[static_cast<size_t>(k)])].data() +
                                 offset[static_cast<size_t>(k)];
        std::copy(from, from + count[static_cast<size_t>(k)],
                  compact.points.begin() + compact.start[static_cast<size_t>(k)]);
      }
    });
  }
  compact.job.assign(static_cast<size_t>(ne), -1);
  compact.unflipped_face.resize(static_cast<size_t>(ne));
  for (int k = 0; k < nk; ++k) compact.job[static_cast<size_t>(flipped.edge[static_cast<size_t>(k)])] = k;
  parallel_chunks(ne, 8192, [&](int begin, int end, int) {
    for (int e = begin; e < end; ++e) {
      // The input halfedge with the edge's tail carries the one segment (same orientation rule as E).
      const int original = original_edge[static_cast<size_t>(e)];
      compact.unflipped_face[static_cast<size_t>(e)] =
          original >= 0 ? input.edge_halfedge[static_cast<size_t>(original)] / 3 : -1;
    }
  });
  return compact;
}

TracedEdges expand_traces(const CompactTraces& compact, const Eigen::MatrixXi& E) {
  const int ne = static_cast<int>(compact.job.size());
  TracedEdges traces;
  traces.start.resize(static_cast<size_t>(ne) + 1);
  traces.start[0] = 0;
  for (int e = 0; e < ne; ++e) {
    const int k = compact.job[static_cast<size_t>(e)];
    traces.start[static_cast<size_t>(e) + 1] =
        traces.start[static_cast<size_t>(e)] +
        (k < 0 ? 2 : compact.start[static_cast<size_t>(k) + 1] - compact.start[static_cast<size_t>(k)]);
  }
  const size_t np = static_cast<size_t>(traces.start.back());
  traces.a.resize(np);
  traces.c.resize(np);
  traces.face.resize(np);
  traces.t.resize(np);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int e = 0; e < ne; ++e) {
    TracePoint ends[2];
    int count = 0;
    const TracePoint* from = compact.edge_points(e, E, ends, count);
    const size_t p = static_cast<size_t>(traces.start[static_cast<size_t>(e)]);
    for (int q = 0; q < count; ++q) {
      traces.a[p + static_cast<size_t>(q)] = from[q].a;
      traces.c[p + static_cast<size_t>(q)] = from[q].c;
      traces.face[p + static_cast<size_t>(q)] = from[q].face;
      traces.t[p + static_cast<size_t>(q)] = from[q].t;
    }
  }
  return traces;
}

} // namespace iarap::detail
