#include "iarap/solver/arap_elements.h"

#include "iarap/core/errors.h"
#include "iarap/core/resident_memory.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"

#include "../intrinsic/segments.h"
#include "../mesh/face_index_range.h"
#include "cell_stiffness.h"
#include "streamed_layout.h"
#include "traced_elements.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace iarap {

namespace {

// Counting sort of (key, value) pairs into CSR form (start: num_keys + 1 entries). for_each_pair(emit)
// calls emit(key, value) for every pair in a fixed order; it runs twice (count, then place) so that no
// list of pairs is stored: on a fresh heap the first touch of such temporaries cost more than the sort.
template <class ForEachPair>
void build_csr(int num_keys, const ForEachPair& for_each_pair, std::vector<int>& start,
               std::vector<int>& out) {
  start.assign(static_cast<size_t>(num_keys) + 2, 0);
  for_each_pair([&](int key, int) { ++start[static_cast<size_t>(key) + 2]; });
  for (int k = 0; k < num_keys; ++k) start[static_cast<size_t>(k) + 2] += start[static_cast<size_t>(k) + 1];
  out.resize(static_cast<size_t>(start[static_cast<size_t>(num_keys) + 1]));
  // start[key + 1] is where the next pair of key goes; once all are placed it is the end of key's run.
  for_each_pair(
      [&](int key, int value) { out[static_cast<size_t>(start[static_cast<size_t>(key) + 1]++)] = value; });
  start.pop_back();
}

// Sizes the per-element arrays for m elements of cells_per_element cells each.
void resize_elements(ArapElements& el, Eigen::Index m, int cells_per_element) {
  el.b_index.resize(m, 3);
  el.b_value.resize(m, 3);
  el.w.resize(m);
  el.face.resize(static_cast<size_t>(m));
  el.cell_start.resize(static_cast<size_t>(m) + 1);
  el.cell.resize(static_cast<size_t>(cells_per_element * m));
}

void check_face_cotangents(const Eigen::MatrixXd& C) {
  for (Eigen::Index f = 0; f < C.rows(); ++f)
    if (!C.row(f).allFinite())
      throw TopologyError("ARAP: face " + std::to_string(f) +
                          " is degenerate (zero area): its cotangent weights are not finite");
}

// b = e_j - e_i in slots 0 and 1; slot 2 unused.
void set_edge_vector(ArapElements& el, Eigen::Index e, int i, int j) {
  el.b_index.row(e) << i, j, i;
  el.b_value.row(e) << -1.0, 1.0, 0.0;
}

// Element x from a segment of the intrinsic edge (tail, head): b with its zero slots pointing at the first
// non-zero's vertex (unused slots may hold any index), the weight and the carrying face. Eq. 16: a segment
// belongs to the cells of both ends of its intrinsic edge.
void set_segment_element(ArapElements& el, int x, const int* index, const double* value, double w, int face,
                         int tail, int head) {
  int first = -1;
  for (int k = 0; k < 3 && first < 0; ++k)
    if (value[k] != 0.0) first = index[k];
  for (int k = 0; k < 3; ++k) {
    el.b_index(x, k) = value[k] != 0.0 ? index[k] : first;
    el.b_value(x, k) = value[k];
  }
  el.w(x) = w;
  el.face[static_cast<size_t>(x)] = face;
  el.cell_start[static_cast<size_t>(x)] = 2 * x;
  el.cell[static_cast<size_t>(2 * x)] = tail;
  el.cell[static_cast<size_t>(2 * x + 1)] = head;
}

// s_hat_e = V^T b_e, summed in slot order (ArapElements::s_hat).
void set_rest_vector(const Eigen::MatrixXd& V, ArapElements& el, Eigen::Index e) {
  for (int d = 0; d < 3; ++d) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) s += el.b_value(e, k) * V(el.b_index(e, k), d);
    el.s_hat(e, d) = s;
  }
}

// Rotation cells of an intrinsic triangulation: one per vertex of its edges, at least one per input vertex
// (inserted boundary points get their own cells). InputError on a negative endpoint.
int intrinsic_cell_count(const Eigen::MatrixXi& E, int num_vertices) {
  int cells = num_vertices;
  for (Eigen::Index e = 0; e < E.rows(); ++e)
    for (int k = 0; k < 2; ++k) {
      if (E(e, k) < 0)
        throw InputError("iARAP: intrinsic edge " + std::to_string(e) + " has endpoint " +
                         std::to_string(E(e, k)));
      cells = std::max(cells, E(e, k) + 1);
    }
  return cells;
}

} // namespace

void release_element_arrays(ArapElements& el) {
  // The cell graph first, from the cell -> elements incidence, in two sweeps (count, then fill) so that no
  // list per cell is allocated: each cell's other cells, marked off in a per-thread array so that each is
  // listed once, then sorted.
  const int cells = el.num_cells;
  el.cell_neighbour_start.assign(static_cast<size_t>(cells) + 1, 0);
  bool shared = false;
  auto for_each_neighbour = [&](int c, std::vector<int>& seen, const auto& visit) {
    for (int k = el.cell_element_start[static_cast<size_t>(c)];
         k < el.cell_element_start[static_cast<size_t>(c) + 1]; ++k) {
      const auto e = static_cast<size_t>(el.cell_element[static_cast<size_t>(k)]);
      for (int j = el.cell_start[e]; j < el.cell_start[e + 1]; ++j) {
        const int other = el.cell[static_cast<size_t>(j)];
        if (other != c && seen[static_cast<size_t>(other)] != c) {
          seen[static_cast<size_t>(other)] = c;
          visit(other);
        }
      }
    }
  };
#pragma omp parallel num_threads(loop_thread_count()) reduction(|| : shared)
  {
    std::vector<int> seen(static_cast<size_t>(cells), -1);
#pragma omp for schedule(static)
    for (int c = 0; c < cells; ++c)
      for_each_neighbour(c, seen, [&](int) { ++el.cell_neighbour_start[static_cast<size_t>(c) + 1]; });
#pragma omp single
    {
      for (int c = 0; c < cells; ++c)
        el.cell_neighbour_start[static_cast<size_t>(c) + 1] +=
            el.cell_neighbour_start[static_cast<size_t>(c)];
      el.cell_neighbour.resize(static_cast<size_t>(el.cell_neighbour_start[static_cast<size_t>(cells)]));
    }
    std::fill(seen.begin(), seen.end(), -1);
#pragma omp for schedule(static)
    for (int c = 0; c < cells; ++c) {
      int* out = el.cell_neighbour.data() + el.cell_neighbour_start[static_cast<size_t>(c)];
      int* const begin = out;
      for_each_neighbour(c, seen, [&](int other) { *out++ = other; });
      std::sort(begin, out);
    }
#pragma omp for schedule(static)
    for (Eigen::Index e = 0; e < el.size(); ++e)
      shared =
          shared || el.cell_start[static_cast<size_t>(e) + 1] - el.cell_start[static_cast<size_t>(e)] > 1;
  }
  el.cells_share_elements = shared;
  el.b_index = {};
  el.b_value = {};
  el.s_hat = {};
  el.w = {};
  std::vector<int>().swap(el.face);
  std::vector<int>().swap(el.cell_start);
  std::vector<int>().swap(el.cell);
  std::vector<int>().swap(el.cell_element_start);
  std::vector<int>().swap(el.cell_element);
  el.arrays_released = true;
}

namespace detail {
void require_element_arrays(const ArapElements& el, const char* what) {
  if (el.arrays_released)
    throw InputError(
        std::string(what) +
        ": the element arrays were released after the precompute (set ArapOptions::keep_elements "
        "to keep them)");
}
} // namespace detail

void check_arap_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3) throw InputError("ARAP: V must be #V x 3, got " + std::to_string(V.cols()) + " columns");
  if (F.cols() != 3) throw InputError("ARAP: F must be #F x 3, got " + std::to_string(F.cols()) + " columns");
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite())
      throw InputError("ARAP: vertex " + std::to_string(v) + " has a non-finite coordinate");
  require_face_indices_in_range(F, V.rows(), "ARAP: ");
}

ArapElements arap_edge_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_arap_mesh(V, F);
  return arap_edge_elements(V, edge_topology(F, static_cast<int>(V.rows())), face_cotangents(V, F));
}

ArapElements arap_edge_elements(const Eigen::MatrixXd& V, const EdgeTopology& topo,
                                const Eigen::MatrixXd& C) {
  const int n = static_cast<int>(V.rows());
  check_face_cotangents(C);
  ArapElements el;
  el.num_vertices = el.num_cells = n;
  const Eigen::Index m = topo.E.rows();
  resize_elements(el, m, 2);
  // An edge of 3 or more faces (a fin) sums the cotangents of all of them: Eq. 1 read as a sum over the
  // faces of the edge, which needs neither manifoldness nor orientation. EdgeTopology keeps two faces per
  // edge, so those edges are summed from the faces' side.
  std::vector<double> fin_weight;
  if (m > 0 && topo.face_count.maxCoeff() > 2) {
    fin_weight.assign(static_cast<size_t>(m), 0.0);
    for (Eigen::Index f = 0; f < topo.FE.rows(); ++f)
      for (int k = 0; k < 3; ++k) fin_weight[static_cast<size_t>(topo.FE(f, k))] += 0.5 * C(f, k);
  }
  for (Eigen::Index e = 0; e < m; ++e) {
    const int i = topo.E(e, 0), j = topo.E(e, 1);
    double w = 0.0; // Eq. 1: w_ij = (cot a + cot b) / 2, kept negative where the mesh is not Delaunay
    for (int s = 0; s < 2; ++s)
      if (topo.EF(e, s) >= 0) w += 0.5 * C(topo.EF(e, s), topo.EK(e, s));
    if (topo.face_count(e) > 2) w = fin_weight[static_cast<size_t>(e)];
    set_edge_vector(el, e, i, j);
    el.w(e) = w;
    el.face[static_cast<size_t>(e)] = topo.EF(e, 0);
    el.cell_start[e] = static_cast<int>(2 * e);
    el.cell[2 * e] = i;
    el.cell[2 * e + 1] = j;
  }
  el.cell_start[m] = static_cast<int>(2 * m);
  detail::finish_elements(V, el);
  return el;
}

ArapElements spokes_rims_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_arap_mesh(V, F);
  return spokes_rims_elements(V, F, face_cotangents(V, F));
}

ArapElements spokes_rims_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                  const Eigen::MatrixXd& C) {
  check_face_cotangents(C);
  ArapElements el;
  el.num_vertices = el.num_cells = static_cast<int>(V.rows());
  const Eigen::Index m = 3 * F.rows();
  resize_elements(el, m, 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index e = 3 * f + k;
      set_edge_vector(el, e, F(f, (k + 1) % 3), F(f, (k + 2) % 3));
      el.w(e) = 0.5 * C(f, k); // Eq. 2: cot of the angle opposite the edge, over 2 per cell term
      el.face[static_cast<size_t>(e)] = static_cast<int>(f);
      el.cell_start[e] = static_cast<int>(3 * e);
      for (int c = 0; c < 3; ++c) el.cell[3 * e + c] = F(f, c);
    }
  el.cell_start[m] = static_cast<int>(3 * m);
  detail::finish_elements(V, el);
  return el;
}

ArapElements iarap_elements(const Eigen::MatrixXd& V, const IntrinsicDelaunay& intrinsic) {
  const Segments& seg = intrinsic.segments;
  const Eigen::MatrixXi& E = intrinsic.triangulation.E;
  const int n = static_cast<int>(V.rows());
  const Eigen::Index count = seg.edge.size();
  if (V.cols() != 3)
    throw InputError("iARAP: V must be #V x 3, got " + std::to_string(V.cols()) + " columns");
  if (seg.b_index.rows() != count || seg.b_value.rows() != count || seg.weight.size() != count ||
      static_cast<Eigen::Index>(seg.face.size()) != count)
    throw InputError("iARAP: segment arrays disagree in length (" + std::to_string(count) + " segments)");
  ArapElements el;
  el.num_vertices = n;
  el.num_cells = intrinsic_cell_count(E, n);
  // Checks as a parallel scan keeping the first bad segment (the error names it); a zero-length segment
  // (b = 0) adds nothing to E, L or the rotations and is left out, so kept[s] numbers the elements.
  const int ns = static_cast<int>(count);
  std::vector<int> kept(static_cast<size_t>(ns) + 1, 0);
  int bad = ns;
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static) reduction(min : bad)
  for (int s = 0; s < ns; ++s) {
    const int edge = seg.edge(s);
    bool ok = edge >= 0 && edge < E.rows() && std::isfinite(seg.weight(s));
    bool nonzero = false;
    for (int k = 0; k < 3; ++k)
      if (seg.b_value(s, k) != 0.0) {
        nonzero = true;
        ok &= seg.b_index(s, k) >= 0 && seg.b_index(s, k) < n;
      }
    if (!ok) bad = std::min(bad, s);
    kept[static_cast<size_t>(s) + 1] = nonzero;
  }
  if (bad < ns) {
    const int edge = seg.edge(bad);
    if (edge < 0 || edge >= E.rows())
      throw InputError("iARAP: segment " + std::to_string(bad) + " names intrinsic edge " +
                       std::to_string(edge) + "; the triangulation has " + std::to_string(E.rows()));
    if (!std::isfinite(seg.weight(bad)))
      throw InputError("iARAP: segment " + std::to_string(bad) + " has a non-finite weight");
    for (int k = 0; k < 3; ++k)
      if (seg.b_value(bad, k) != 0.0 && (seg.b_index(bad, k) < 0 || seg.b_index(bad, k) >= n))
        throw InputError("iARAP: segment " + std::to_string(bad) + " uses vertex " +
                         std::to_string(seg.b_index(bad, k)) + "; mesh has " + std::to_string(n));
  }
  for (int s = 0; s < ns; ++s) kept[static_cast<size_t>(s) + 1] += kept[static_cast<size_t>(s)];
  const int m = kept[static_cast<size_t>(ns)];
  resize_elements(el, m, 2);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int s = 0; s < ns; ++s) {
    const int x = kept[static_cast<size_t>(s)];
    if (kept[static_cast<size_t>(s) + 1] > x)
      set_segment_element(el, x, &seg.b_index(s, 0), &seg.b_value(s, 0), seg.weight(s), seg.face(s),
                          E(seg.edge(s), 0), E(seg.edge(s), 1));
  }
  el.cell_start[static_cast<size_t>(m)] = 2 * m;
  detail::finish_elements(V, el);
  return el;
}

namespace detail {

void finish_elements(const Eigen::MatrixXd& V, ArapElements& el, bool has_rest_vectors, bool release_arrays) {
  const Eigen::Index m = el.size();
  if (!has_rest_vectors) {
    el.s_hat.resize(m, 3);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
    for (Eigen::Index e = 0; e < m; ++e) set_rest_vector(V, el, e);
  }
  build_csr(
      el.num_cells,
      [&](const auto& emit) {
        for (Eigen::Index e = 0; e < m; ++e)
          for (int c = el.cell_start[e]; c < el.cell_start[e + 1]; ++c) emit(el.cell[c], static_cast<int>(e));
      },
      el.cell_element_start, el.cell_element);
  el.streamed =
      std::make_shared<const detail::StreamedLayout>(detail::streamed_layout(V, el, release_arrays));
}

ArapElements traced_iarap_elements(const Eigen::MatrixXd& V, const IntrinsicTriangulation& tri,
                                   const CompactTraces& traces) {
  const int n = static_cast<int>(V.rows());
  const int ne = static_cast<int>(tri.E.rows());
  ArapElements el;
  el.num_vertices = n;
  el.num_cells = intrinsic_cell_count(tri.E, n);
  const Eigen::VectorXi start = segment_offsets(traces, ne);
  const int ns = start(ne);
  resize_elements(el, ns, 2);
  el.s_hat.resize(ns, 3);
  // One element per segment, with the segment's rest vector: the sum finish_elements would compute, in the
  // same order (where a zero slot names another vertex, only the sign of a zero can differ). A segment with
  // b = 0 is marked and squeezed out after, as iarap_elements leaves it out.
  std::vector<char> empty(static_cast<size_t>(ns), 0);
  for_each_segment(V, tri, traces, start, [&](int s, int e, const SegmentVector& segment) {
    set_segment_element(el, s, segment.index, segment.value, segment.weight, segment.face, tri.E(e, 0),
                        tri.E(e, 1));
    for (int d = 0; d < 3; ++d) el.s_hat(s, d) = segment.s_hat(d);
    empty[static_cast<size_t>(s)] =
        segment.value[0] == 0.0 && segment.value[1] == 0.0 && segment.value[2] == 0.0;
  });
  if (std::count(empty.begin(), empty.end(), 1) > 0) drop_two_cell_elements(el, empty);
  el.cell_start[static_cast<size_t>(el.size())] = static_cast<int>(2 * el.size());
  return el;
}

void drop_two_cell_elements(ArapElements& el, const std::vector<char>& drop) {
  const Eigen::Index count = el.size();
  int m = 0;
  for (Eigen::Index s = 0; s < count; ++s) {
    if (drop[static_cast<size_t>(s)]) continue;
    el.b_index.row(m) = el.b_index.row(s);
    el.b_value.row(m) = el.b_value.row(s);
    el.s_hat.row(m) = el.s_hat.row(s);
    el.w(m) = el.w(s);
    el.face[static_cast<size_t>(m)] = el.face[static_cast<size_t>(s)];
    el.cell[static_cast<size_t>(2 * m)] = el.cell[static_cast<size_t>(2 * s)];
    el.cell[static_cast<size_t>(2 * m + 1)] = el.cell[static_cast<size_t>(2 * s + 1)];
    ++m;
  }
  el.b_index.conservativeResize(m, 3);
  el.b_value.conservativeResize(m, 3);
  el.s_hat.conservativeResize(m, 3);
  el.w.conservativeResize(m);
  el.face.resize(static_cast<size_t>(m));
  el.cell_start.resize(static_cast<size_t>(m) + 1);
  el.cell.resize(static_cast<size_t>(2 * m));
  el.cell_start[static_cast<size_t>(m)] = 2 * m;
}

} // namespace detail

Eigen::SparseMatrix<double> element_system_matrix(const ArapElements& el) {
  detail::require_element_arrays(el, "system matrix");
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(9 * el.size()));
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const double cw = detail::element_cell_weight(el, e) * el.w(e); // |cells(e)| w_e, or sum s_c w_e
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const double v = cw * (el.b_value(e, k) * el.b_value(e, l)); // bitwise symmetric
        if (v != 0.0) triplets.emplace_back(el.b_index(e, k), el.b_index(e, l), v);
      }
  }
  Eigen::SparseMatrix<double> L(el.num_vertices, el.num_vertices);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace iarap
