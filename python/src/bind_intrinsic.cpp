// The intrinsic Delaunay triangulation with its traced edges and segments (paper Sections 2 and 4).
#include "bindings.h"
#include "numpy_arrays.h"

#include "iarap/intrinsic/intrinsic_delaunay.h"

namespace iarap::python {
namespace {

py::dict triangulation_dict(const IntrinsicDelaunay& idt) {
  const IntrinsicTriangulation& t = idt.triangulation;
  py::dict d;
  d["F"] = to_numpy(t.F);
  d["FE"] = to_numpy(t.FE);
  d["E"] = to_numpy(t.E);
  d["length"] = to_numpy(t.length);
  d["cot_weight"] = to_numpy(t.cot_weight);
  d["corner_angle"] = to_numpy(t.corner_angle);
  d["face_area"] = to_numpy(t.face_area);
  d["is_boundary"] = to_numpy(t.is_boundary).attr("astype")("bool");
  d["original_edge"] = to_numpy(t.original_edge);
  d["num_input_vertices"] = t.num_input_vertices;
  d["inserted_on"] = to_numpy(t.inserted_on);
  d["inserted_t"] = to_numpy(t.inserted_t);
  d["obtuse_boundary_before"] = t.obtuse_boundary_before;
  d["obtuse_boundary_after"] = t.obtuse_boundary_after;
  d["refine_rounds"] = t.refine_rounds;
  d["flips"] = t.flips;
  d["non_delaunay_before"] = t.non_delaunay_before;
  d["non_delaunay_after"] = t.non_delaunay_after;
  d["mollify_delta"] = t.mollify_delta;
  return d;
}

py::dict segments_dict(const Segments& s) {
  py::dict d;
  d["edge"] = to_numpy(s.edge);
  d["face"] = to_numpy(s.face);
  d["b_index"] = to_numpy(s.b_index);
  d["b_value"] = to_numpy(s.b_value);
  d["s_hat"] = to_numpy(s.s_hat);
  d["length"] = to_numpy(s.length);
  d["weight"] = to_numpy(s.weight);
  d["edge_start"] = to_numpy(s.edge_start);
  return d;
}

py::dict traces_dict(const TracedEdges& traces) {
  py::dict d;
  d["start"] = to_numpy(traces.start);
  d["a"] = to_numpy(traces.a);
  d["c"] = to_numpy(traces.c);
  d["face"] = to_numpy(traces.face);
  d["t"] = to_numpy(traces.t);
  return d;
}

py::dict intrinsic_delaunay_py(const py::object& V, const py::object& F, double delaunay_tolerance,
                               bool mollify, double mollify_epsilon, bool refine_boundary,
                               int max_boundary_insertions) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  IntrinsicOptions options;
  options.delaunay_tolerance = delaunay_tolerance;
  options.mollify = mollify;
  options.mollify_epsilon = mollify_epsilon;
  options.refine_boundary = refine_boundary;
  options.max_boundary_insertions = max_boundary_insertions;
  IntrinsicDelaunay idt;
  {
    py::gil_scoped_release release;
    idt = intrinsic_delaunay(positions, faces, options);
  }
  py::dict d = triangulation_dict(idt);
  d["segments"] = segments_dict(idt.segments);
  d["B"] = to_csr(idt.segments.B);
  d["traces"] = traces_dict(idt.traces);
  d["flip_ms"] = idt.flip_ms;
  d["trace_ms"] = idt.trace_ms;
  d["segment_ms"] = idt.segment_ms;
  return d;
}

} // namespace

void bind_intrinsic(py::module_& m) {
  m.def("intrinsic_delaunay", &intrinsic_delaunay_py, py::arg("V"), py::arg("F"), py::kw_only(),
        py::arg("delaunay_tolerance") = 1e-12, py::arg("mollify") = true, py::arg("mollify_epsilon") = 1e-6,
        py::arg("refine_boundary") = false, py::arg("max_boundary_insertions") = -1,
        R"(Intrinsic Delaunay triangulation of (V (#V, 3), F (#F, 3)), its edges traced over the input and cut
into segments s = V^T b (paper Eq. 7-8, 11). Returns a dict:

F (#F, 3) intrinsic faces (input vertex indices), FE (#F, 3) intrinsic edge opposite each corner,
E (#E, 2) edge endpoints, length (#E,) intrinsic edge lengths (mesh units), cot_weight (#E,)
w_ij = (cot a + cot b) / 2, corner_angle (#F, 3) radians, face_area (#F,) squared mesh units,
is_boundary (#E,) bool, original_edge (#E,) input edge index or -1, flips, non_delaunay_before,
non_delaunay_after, mollify_delta (mesh units), and for refine_boundary: num_input_vertices (#V),
inserted_on (#P, 2) input boundary edge of each inserted point, inserted_t (#P,) its position on that edge
(intrinsic vertex #V + q is point q), obtuse_boundary_before, obtuse_boundary_after, refine_rounds;
segments: dict of edge (#S,), face (#S,), b_index (#S, 3), b_value (#S, 3), s_hat (#S, 3) rest vectors,
length (#S,), weight (#S,) w_ij |e_ij| / |s| (Eq. 11), edge_start (#E + 1,) offsets of each edge's segments;
B: scipy.sparse.csr_matrix (#S, #V), row s holds b_s (at most 3 non-zeros, summing to 0), L = B^T D_w B;
traces: dict of start (#E + 1,), a, c, face, t: point p of the polyline is (1 - t) V[a] + t V[c] (c = -1 for
an input vertex); flip_ms, trace_ms, segment_ms (milliseconds).
delaunay_tolerance: flip while cot a + cot b < -tolerance (dimensionless). mollify / mollify_epsilon:
intrinsic mollification of (nearly) degenerate triangles (Sharp and Crane 2020). refine_boundary: split
boundary edges opposite an obtuse angle at the altitude foot until none is left (not in the paper), at most
max_boundary_insertions points (-1: 4 x #boundary edges + 100).
Raises ValueError for bad arrays or a non-manifold mesh.)");
}

} // namespace iarap::python
