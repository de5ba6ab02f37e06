#include "iarap/solver/system_pattern.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/edge_topology.h"

#include "cell_stiffness.h"
#include "traced_elements.h"

#include <string>
#include <vector>

namespace iarap {

SystemPattern system_pattern(const Eigen::MatrixXi& F, int num_vertices) {
  return system_pattern(F, num_vertices, edge_topology(F, num_vertices));
}

SystemPattern system_pattern(const Eigen::MatrixXi& F, int num_vertices, const EdgeTopology& topo) {
  const int nv = num_vertices, ne = static_cast<int>(topo.E.rows()), nf = static_cast<int>(F.rows());
  // Column j holds j and its edge neighbours. Edges come sorted by (E(e,0), E(e,1)), so filling the
  // columns in edge order and putting the diagonal between the smaller and larger rows keeps rows sorted:
  // column j receives first the rows i < j (edges (i, j), increasing i), then j, then i > j.
  std::vector<int> count(static_cast<size_t>(nv), 1);
  for (int e = 0; e < ne; ++e) {
    ++count[static_cast<size_t>(topo.E(e, 0))];
    ++count[static_cast<size_t>(topo.E(e, 1))];
  }
  SystemPattern p;
  p.matrix.resize(nv, nv);
  int* outer = p.matrix.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < nv; ++j) outer[j + 1] = outer[j] + count[static_cast<size_t>(j)];
  p.matrix.resizeNonZeros(outer[nv]);
  int* inner = p.matrix.innerIndexPtr();
  std::fill(p.matrix.valuePtr(), p.matrix.valuePtr() + outer[nv], 0.0);
  std::vector<int> fill(outer, outer + nv);
  // Where each entry goes, kept for the face slots below: lower[e] holds (i, j), upper[e] (j, i), diagonal[j]
  // (j, j).
  std::vector<int> lower(static_cast<size_t>(ne)), upper(static_cast<size_t>(ne)),
      diagonal(static_cast<size_t>(nv));
  // Edge e = (i, j), i < j: row i of column j (its lower rows, in increasing i) ...
  for (int e = 0; e < ne; ++e) {
    const int at = fill[static_cast<size_t>(topo.E(e, 1))]++;
    inner[at] = topo.E(e, 0);
    lower[static_cast<size_t>(e)] = at;
  }
  for (int j = 0; j < nv; ++j) {
    const int at = fill[static_cast<size_t>(j)]++;
    inner[at] = j;
    diagonal[static_cast<size_t>(j)] = at;
  }
  // ... then row j of column i, in increasing j for each i.
  for (int e = 0; e < ne; ++e) {
    const int at = fill[static_cast<size_t>(topo.E(e, 0))]++;
    inner[at] = topo.E(e, 1);
    upper[static_cast<size_t>(e)] = at;
  }

  // Slot of (r, c) = (F(f, k), F(f, l)) for each face: the diagonal, or the entry of the face's edge
  // opposite its third corner, at the position recorded above (2.77M vertices, one thread: the pattern 2.3 ->
  // 1.9 s against a search down the column for each of the 9 pairs). The search stays for a topology that
  // is not F's (the edge is then not (r, c)).
  const auto search = [&](int r, int c) {
    for (int k = outer[c]; k < outer[c + 1]; ++k)
      if (inner[k] == r) return k;
    return -1; // unreachable: the pattern holds every face's pairs
  };
  const auto slot = [&](int f, int k, int l) {
    const int r = F(f, k), c = F(f, l);
    if (r == c) return diagonal[static_cast<size_t>(c)];
    const int e = topo.FE(f, 3 - k - l);
    if (topo.E(e, 0) == r && topo.E(e, 1) == c) return lower[static_cast<size_t>(e)];
    if (topo.E(e, 0) == c && topo.E(e, 1) == r) return upper[static_cast<size_t>(e)];
    return search(r, c);
  };
  p.face_slot.resize(nf, 9);
  // loop_thread_count(): in arap_precompute this runs beside the element or intrinsic build and must not
  // open a team on the core that build is using.
#pragma omp parallel for num_threads(loop_thread_count()) schedule(static)
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) p.face_slot(f, 3 * k + l) = slot(f, k, l);
  return p;
}

Eigen::SparseMatrix<double> element_system_matrix(const ArapElements& el, const Eigen::MatrixXi& F,
                                                  const SystemPattern& pattern) {
  detail::require_element_arrays(el, "system matrix");
  Eigen::SparseMatrix<double> L = pattern.matrix;
  double* value = L.valuePtr();
  const int nf = static_cast<int>(F.rows());
  if (el.face.size() != static_cast<size_t>(el.size()))
    throw InputError("system matrix: " + std::to_string(el.face.size()) + " element faces for " +
                     std::to_string(el.size()) + " elements");
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    const int f = el.face[static_cast<size_t>(e)];
    if (f < 0 || f >= nf)
      throw InputError("system matrix: element " + std::to_string(e) + " names face " + std::to_string(f) +
                       "; the mesh has " + std::to_string(nf));
    int corner[3];
    for (int k = 0; k < 3; ++k) {
      corner[k] = -1;
      if (el.b_value(e, k) == 0.0) continue;
      for (int c = 0; c < 3; ++c)
        if (F(f, c) == el.b_index(e, k)) corner[k] = c;
      if (corner[k] < 0)
        throw InputError("system matrix: element " + std::to_string(e) + " has vertex " +
                         std::to_string(el.b_index(e, k)) + " outside its face " + std::to_string(f));
    }
    const double cw = detail::element_cell_weight(el, e) * el.w(e); // |cells(e)| w_e, or sum s_c w_e
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l)
        if (corner[k] >= 0 && corner[l] >= 0) // same products as the triplet assembly: bitwise symmetric
          value[pattern.face_slot(f, 3 * corner[k] + corner[l])] +=
              cw * (el.b_value(e, k) * el.b_value(e, l));
  }
  return L;
}

Eigen::SparseMatrix<double> cotan_system_matrix(const Eigen::MatrixXi& F, const Eigen::MatrixXd& C,
                                                const SystemPattern& pattern) {
  Eigen::SparseMatrix<double> L = pattern.matrix;
  double* value = L.valuePtr();
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      // The edge (a, b) opposite corner k: C(f, k) (e_a - e_b)(e_a - e_b)^T, i.e. 2 x (cot / 2) per side.
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      const double c = C(f, k);
      value[pattern.face_slot(f, 3 * a + a)] += c;
      value[pattern.face_slot(f, 3 * b + b)] += c;
      value[pattern.face_slot(f, 3 * a + b)] -= c;
      value[pattern.face_slot(f, 3 * b + a)] -= c;
    }
  return L;
}

} // namespace iarap
