#include "iarap/solver/arap_elements.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap {

namespace {

// Counting sort of (key, value) pairs into CSR form: start has num_keys + 1 entries.
void build_csr(int num_keys, const std::vector<int>& keys, const std::vector<int>& values,
               std::vector<int>& start, std::vector<int>& out) {
  start.assign(static_cast<size_t>(num_keys) + 1, 0);
  for (int k : keys)
    ++start[static_cast<size_t>(k) + 1];
  for (int k = 0; k < num_keys; ++k)
    start[k + 1] += start[k];
  out.resize(keys.size());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (size_t i = 0; i < keys.size(); ++i)
    out[static_cast<size_t>(next[keys[i]]++)] = values[i];
}

// Rest vectors and the two transposed incidences, from b, w and the element -> cell CSR.
void finish_elements(const Eigen::MatrixXd& V, ArapElements& el) {
  const Eigen::Index m = el.size();
  el.s_hat.resize(m, 3);
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (Eigen::Index e = 0; e < m; ++e)
    for (int d = 0; d < 3; ++d) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k)
        s += el.b_value(e, k) * V(el.b_index(e, k), d);
      el.s_hat(e, d) = s;
    }
  std::vector<int> keys, values;
  keys.reserve(el.cell.size());
  values.reserve(el.cell.size());
  for (Eigen::Index e = 0; e < m; ++e)
    for (int c = el.cell_start[e]; c < el.cell_start[e + 1]; ++c) {
      keys.push_back(el.cell[c]);
      values.push_back(static_cast<int>(e));
    }
  build_csr(el.num_cells, keys, values, el.cell_element_start, el.cell_element);
  keys.clear();
  values.clear();
  for (Eigen::Index e = 0; e < m; ++e)
    for (int k = 0; k < 3; ++k)
      if (el.b_value(e, k) != 0.0) {
        keys.push_back(el.b_index(e, k));
        values.push_back(static_cast<int>(3 * e + k));
      }
  build_csr(el.num_vertices, keys, values, el.vertex_slot_start, el.vertex_slot);
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

} // namespace

void check_arap_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3)
    throw InputError("ARAP: V must be #V x 3, got " + std::to_string(V.cols()) + " columns");
  if (F.cols() != 3)
    throw InputError("ARAP: F must be #F x 3, got " + std::to_string(F.cols()) + " columns");
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite())
      throw InputError("ARAP: vertex " + std::to_string(v) + " has a non-finite coordinate");
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= V.rows())
        throw InputError("ARAP: face " + std::to_string(f) + " uses vertex " + std::to_string(F(f, k)) +
                         "; mesh has " + std::to_string(V.rows()));
}

ArapElements arap_edge_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_arap_mesh(V, F);
  const int n = static_cast<int>(V.rows());
  const EdgeTopology topo = edge_topology(F, n);
  const Eigen::MatrixXd C = face_cotangents(V, F);
  check_face_cotangents(C);
  ArapElements el;
  el.num_vertices = el.num_cells = n;
  const Eigen::Index m = topo.E.rows();
  resize_elements(el, m, 2);
  for (Eigen::Index e = 0; e < m; ++e) {
    const int i = topo.E(e, 0), j = topo.E(e, 1);
    if (topo.face_count(e) > 2)
      throw TopologyError("ARAP: edge " + std::to_string(e) + " (" + std::to_string(i) + ", " +
                          std::to_string(j) + ") has " + std::to_string(topo.face_count(e)) +
                          " faces; the mesh must be manifold");
    double w = 0.0; // Eq. 1: w_ij = (cot a + cot b) / 2, kept negative where the mesh is not Delaunay
    for (int s = 0; s < 2; ++s)
      if (topo.EF(e, s) >= 0)
        w += 0.5 * C(topo.EF(e, s), topo.EK(e, s));
    set_edge_vector(el, e, i, j);
    el.w(e) = w;
    el.face[static_cast<size_t>(e)] = topo.EF(e, 0);
    el.cell_start[e] = static_cast<int>(2 * e);
    el.cell[2 * e] = i;
    el.cell[2 * e + 1] = j;
  }
  el.cell_start[m] = static_cast<int>(2 * m);
  finish_elements(V, el);
  return el;
}

ArapElements spokes_rims_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_arap_mesh(V, F);
  const Eigen::MatrixXd C = face_cotangents(V, F);
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
      for (int c = 0; c < 3; ++c)
        el.cell[3 * e + c] = F(f, c);
    }
  el.cell_start[m] = static_cast<int>(3 * m);
  finish_elements(V, el);
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
  el.num_vertices = el.num_cells = n;
  for (Eigen::Index e = 0; e < E.rows(); ++e)
    for (int k = 0; k < 2; ++k) {
      if (E(e, k) < 0)
        throw InputError("iARAP: intrinsic edge " + std::to_string(e) + " has endpoint " +
                         std::to_string(E(e, k)));
      el.num_cells = std::max(el.num_cells, E(e, k) + 1); // inserted boundary points get their own cells
    }
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
      throw InputError("iARAP: segment " + std::to_string(bad) + " names intrinsic edge " + std::to_string(edge) +
                       "; the triangulation has " + std::to_string(E.rows()));
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
    if (kept[static_cast<size_t>(s) + 1] == x) continue;
    int first = -1;
    for (int k = 0; k < 3 && first < 0; ++k)
      if (seg.b_value(s, k) != 0.0) first = seg.b_index(s, k);
    for (int k = 0; k < 3; ++k) {
      const double value = seg.b_value(s, k);
      el.b_index(x, k) = value != 0.0 ? seg.b_index(s, k) : first; // unused slots may hold any index
      el.b_value(x, k) = value;
    }
    el.w(x) = seg.weight(s);
    el.face[static_cast<size_t>(x)] = seg.face(s);
    el.cell_start[static_cast<size_t>(x)] = 2 * x;
    el.cell[static_cast<size_t>(2 * x)] = E(seg.edge(s), 0); // Eq. 16: a segment belongs to the cells of both
    el.cell[static_cast<size_t>(2 * x + 1)] = E(seg.edge(s), 1); // ends of its intrinsic edge
  }
  el.cell_start[static_cast<size_t>(m)] = 2 * m;
  finish_elements(V, el);
  return el;
}

Eigen::SparseMatrix<double> element_system_matrix(const ArapElements& el) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(9 * el.size()));
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const double cw = (el.cell_start[e + 1] - el.cell_start[e]) * el.w(e); // |cells(e)| w_e
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) {
        const double v = cw * (el.b_value(e, k) * el.b_value(e, l)); // bitwise symmetric
        if (v != 0.0)
          triplets.emplace_back(el.b_index(e, k), el.b_index(e, l), v);
      }
  }
  Eigen::SparseMatrix<double> L(el.num_vertices, el.num_vertices);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace iarap
