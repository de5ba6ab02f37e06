#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/core/stopwatch.h"

#include "intrinsic_phases.h"
#include "segments.h"
#include "signpost_triangulation.h"
#include "trace_edges.h"

#include "iarap/core/threads.h"
#include "iarap/mesh/cotan.h"

#include "../core/parallel_chunks.h"

#include <vector>

namespace iarap {

namespace {

// inserted_ends: the input boundary edge (tail, head) of each inserted point, 2 per point. Without
// `with_faces`, F, FE, corner_angle and face_area stay empty.
IntrinsicTriangulation export_triangulation(const detail::SignpostTriangulation& tri,
                                            const std::vector<int>& inserted_ends, bool with_faces) {
  const int nf = with_faces ? tri.num_faces() : 0, ne = tri.num_edges();
  IntrinsicTriangulation out;
  out.F.resize(nf, 3);
  out.FE.resize(nf, 3);
  out.corner_angle.resize(nf, 3);
  out.face_area.resize(nf);
  detail::parallel_chunks(nf, 8192, [&](int begin, int end, int) {
    for (int f = begin; f < end; ++f) {
      out.face_area(f) = triangle_area_from_lengths(
          tri.halfedge_length(3 * f), tri.halfedge_length(3 * f + 1), tri.halfedge_length(3 * f + 2));
      for (int k = 0; k < 3; ++k) {
        const int h = 3 * f + k;
        out.F(f, k) = tri.tail(h);
        out.FE(f, (k + 2) % 3) = tri.edge[static_cast<size_t>(h)]; // halfedge k is opposite corner k + 2
        out.corner_angle(f, k) = tri.angle[static_cast<size_t>(h)];
      }
    }
  });
  out.E.resize(ne, 2);
  out.length.resize(ne);
  out.cot_weight.resize(ne);
  out.is_boundary.resize(ne);
  out.original_edge.resize(ne);
  detail::parallel_chunks(ne, 8192, [&](int begin, int end, int) {
    for (int e = begin; e < end; ++e) {
      const int h = tri.edge_halfedge[static_cast<size_t>(e)];
      out.E(e, 0) = tri.edge_vertex[static_cast<size_t>(2 * e)];
      out.E(e, 1) = tri.edge_vertex[static_cast<size_t>(2 * e + 1)];
      out.length(e) = tri.length[static_cast<size_t>(e)];
      const int t = tri.twin[static_cast<size_t>(h)];
      out.cot_weight(e) =
          0.5 * (tri.cot[static_cast<size_t>(h)] + (t >= 0 ? tri.cot[static_cast<size_t>(t)] : 0.0));
      out.is_boundary(e) = t < 0;
      out.original_edge(e) = tri.original_edge[static_cast<size_t>(e)];
    }
  });
  out.mollify_delta = tri.mollify_delta;
  out.num_input_vertices = tri.num_input_vertices;
  const int np = tri.num_vertices - tri.num_input_vertices;
  out.inserted_on.resize(np, 2);
  out.inserted_t.resize(np);
  for (int q = 0; q < np; ++q) {
    out.inserted_on(q, 0) = inserted_ends[static_cast<size_t>(2 * q)];
    out.inserted_on(q, 1) = inserted_ends[static_cast<size_t>(2 * q + 1)];
    out.inserted_t(q) = tri.inserted_t[static_cast<size_t>(q)];
  }
  return out;
}

} // namespace

namespace detail {

namespace {

// Flips a built triangulation to Delaunay and, if asked, refines its obtuse boundary edges.
void flip_built(FlippedTriangulation& out, const IntrinsicOptions& options) {
  // The tracer and the boundary refinement read the unflipped connectivity, lengths and angles only.
  out.input = input_triangulation(out.tri);
  out.stats = flip_to_delaunay(out.tri, options.delaunay_tolerance);
  if (!options.refine_boundary) { // refine_obtuse_boundary counts the obtuse boundary edges itself
    out.refine.obtuse_before = out.refine.obtuse_after =
        count_obtuse_boundary_edges(out.tri, options.delaunay_tolerance);
  } else {
    int boundary_edges = 0;
    for (const auto& h : out.input.halfedge) boundary_edges += h.twin < 0;
    const int cap =
        options.max_boundary_insertions >= 0 ? options.max_boundary_insertions : 4 * boundary_edges + 100;
    out.refine = refine_obtuse_boundary(out.tri, out.input, options.delaunay_tolerance, cap);
  }
  out.non_delaunay_after = out.refine.inserted > 0 ? count_non_delaunay(out.tri, options.delaunay_tolerance)
                                                   : out.stats.non_delaunay_after;
}

} // namespace

FlippedTriangulation flip_phase(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                const IntrinsicOptions& options, SignpostInput* input) {
  const auto t0 = Clock::now();
  FlippedTriangulation out;
  out.tri = build_signpost_triangulation(V, F, options.mollify, options.mollify_epsilon, out.fans,
                                         options.refine_boundary, input);
  flip_built(out, options);
  out.flip_ms = ms_since(t0);
  return out;
}

FlippedTriangulation flip_cover_phase(const TuftedCover& cover, const IntrinsicOptions& options) {
  const auto t0 = Clock::now();
  FlippedTriangulation out;
  out.tri = build_glued_signpost_triangulation(cover.V, cover.F, cover.twin, options.mollify,
                                               options.mollify_epsilon, out.fans);
  flip_built(out, options); // the cover has no boundary: nothing to refine
  out.flip_ms = ms_since(t0);
  return out;
}

TracedTriangulation trace_phase(FlippedTriangulation&& flipped, bool with_faces) {
  TracedTriangulation result;
  result.flip_ms = flipped.flip_ms;
  SignpostTriangulation& tri = flipped.tri;
  // The tracer needs little of the flipped triangulation: its flipped edges (a compact list), and the
  // endpoints of the others. The input copy and its fans are released right after tracing, before the
  // triangulation is exported, so that the three are never in memory with the export.
  auto t0 = Clock::now();
  {
    const EdgesToTrace flipped_edges_list = flipped_edges(tri);
    std::vector<double>().swap(tri.phi);
    result.traces = trace_edges(flipped.input, flipped.fans, flipped_edges_list, tri.original_edge);
  }
  std::vector<int> inserted_ends;
  for (int hb : tri.inserted_halfedge) {
    inserted_ends.push_back(flipped.input.tail(hb));
    inserted_ends.push_back(flipped.input.head(hb));
  }
  flipped.input = {};
  flipped.fans = {};
  result.trace_ms = ms_since(t0);

  t0 = Clock::now();
  result.triangulation = export_triangulation(tri, inserted_ends, with_faces);
  tri = {};
  IntrinsicTriangulation& out = result.triangulation;
  out.obtuse_boundary_before = flipped.refine.obtuse_before;
  out.obtuse_boundary_after = flipped.refine.obtuse_after;
  out.refine_rounds = flipped.refine.rounds;
  out.flips = flipped.stats.flips + flipped.refine.flips;
  out.non_delaunay_before = flipped.stats.non_delaunay_before;
  out.non_delaunay_after = flipped.non_delaunay_after;
  result.flip_ms += ms_since(t0);
  return result;
}

} // namespace detail

IntrinsicDelaunay intrinsic_delaunay(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const IntrinsicOptions& options) {
  detail::TracedTriangulation traced = detail::trace_phase(detail::flip_phase(V, F, options));
  IntrinsicDelaunay result;
  result.flip_ms = traced.flip_ms;
  result.trace_ms = traced.trace_ms;
  result.triangulation = std::move(traced.triangulation);
  auto t0 = Clock::now();
  result.segments = detail::build_segments(V, result.triangulation, traced.traces, options.assemble_B);
  result.segment_ms = ms_since(t0);
  if (options.keep_traces) {
    t0 = Clock::now();
    result.traces = detail::expand_traces(traced.traces, result.triangulation.E);
    result.trace_ms += ms_since(t0);
  }
  return result;
}

} // namespace iarap
