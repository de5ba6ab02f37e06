#include "iarap/laplacian/first_segment_laplacians.h"

#include "iarap/core/errors.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace iarap {

namespace {

// The first segment of intrinsic edge e seen from its end `end` (0: E(e,0), 1: E(e,1)), from v_i to the far
// point p = (1 - t) v_a + t v_c (or the vertex v_a), as beta = e_i - (barycentric p): its b oriented so
// beta_i = +1.
struct FirstSegment {
  int i;          // the vertex it starts from
  int n;          // entries of beta in use (2 when p is a vertex)
  int index[3];   // i, a, c
  double beta[3]; // 1, -(1 - t), -t
  double omega;   // ||*e_ij|| / ||p - v_i|| = w_ij |e_ij| / |s| (Eq. 11 weight of this segment)
};

// Every (edge, end) pair except loops, from the traces: the point after the start for end 0, the point
// before the last for end 1 (the last segment reversed).
std::vector<FirstSegment> first_segments(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt) {
  const IntrinsicTriangulation& T = idt.triangulation;
  const TracedEdges& traces = idt.traces;
  std::vector<FirstSegment> result;
  result.reserve(static_cast<size_t>(2 * T.E.rows()));
  for (int e = 0; e < static_cast<int>(T.E.rows()); ++e) {
    const int i0 = T.E(e, 0), i1 = T.E(e, 1);
    if (i0 == i1) continue; // loop: its intrinsic flux w (f_i - f_i) is zero
    const int first = traces.start[static_cast<size_t>(e)],
              last = traces.start[static_cast<size_t>(e) + 1] - 1;
    if (last - first < 1)
      throw TopologyError("intrinsic edge " + std::to_string(e) + " (" + std::to_string(i0) + ", " +
                          std::to_string(i1) + ") has a trace of " + std::to_string(last - first + 1) +
                          " point(s); at least 2 needed");
    const double flux = T.cot_weight(e) * T.length(e); // ||*e_ij|| = w_ij |e_ij|
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? i0 : i1;
      const auto p = static_cast<size_t>(end == 0 ? first + 1 : last - 1);
      const int a = traces.a[p], c = traces.c[p];
      if (a < 0 || a >= V.rows() || c >= V.rows())
        throw TopologyError("intrinsic edge " + std::to_string(e) + ": trace point " + std::to_string(p) +
                            " uses vertices (" + std::to_string(a) + ", " + std::to_string(c) +
                            "); the mesh has " + std::to_string(V.rows()));
      const double t = c < 0 ? 0.0 : traces.t[p];
      FirstSegment s{i, c < 0 ? 2 : 3, {i, a, std::max(c, 0)}, {1.0, -(1.0 - t), -t}, 0.0};
      Eigen::RowVector3d point = V.row(a);
      if (c >= 0) point = (1.0 - t) * V.row(a) + t * V.row(c);
      const double length = (point - V.row(i)).norm();
      if (!(length > 0.0))
        throw TopologyError("intrinsic edge " + std::to_string(e) + " (" + std::to_string(i0) + ", " +
                            std::to_string(i1) + "): its first segment from vertex " + std::to_string(i) +
                            " has zero length");
      s.omega = flux / length;
      result.push_back(s);
    }
  }
  return result;
}

// #V x #V matrix from the triplets emit(s, triplets) appends for each first segment s.
template <typename Emit>
Eigen::SparseMatrix<double> assemble(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt,
                                     size_t entries_per_segment, Emit emit) {
  const std::vector<FirstSegment> segments = first_segments(V, idt);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(entries_per_segment * segments.size());
  for (const FirstSegment& s : segments) emit(s, triplets);
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace

Eigen::SparseMatrix<double> iarap_plus_laplacian(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt) {
  // Row i gets omega (f_i - f_p) = omega beta^T f: the finite-volume flux through *e_ij, f_j replaced by f_p.
  return assemble(V, idt, 3, [](const FirstSegment& s, std::vector<Eigen::Triplet<double>>& triplets) {
    for (int k = 0; k < s.n; ++k) triplets.emplace_back(s.i, s.index[k], s.omega * s.beta[k]);
  });
}

Eigen::SparseMatrix<double> iarap_sym_laplacian(const Eigen::MatrixXd& V, const IntrinsicDelaunay& idt) {
  // Hessian of (omega / 2) |V beta - R V_hat beta|^2: each end carries half the edge, as in Eq. 9.
  return assemble(V, idt, 9, [](const FirstSegment& s, std::vector<Eigen::Triplet<double>>& triplets) {
    for (int r = 0; r < s.n; ++r)
      for (int k = 0; k < s.n; ++k)
        triplets.emplace_back(s.index[r], s.index[k], 0.5 * s.omega * s.beta[r] * s.beta[k]);
  });
}

} // namespace iarap
