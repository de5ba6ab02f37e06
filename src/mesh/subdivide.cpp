#include "iarap/mesh/subdivide.h"
#include "face_index_range.h"

#include <utility>

#include "iarap/mesh/edge_topology.h"

namespace iarap {

void subdivide_midpoint(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::MatrixXd& V_out,
                        Eigen::MatrixXi& F_out) {
  require_triangle_mesh(V, F, "subdivide_midpoint");
  const int nv = static_cast<int>(V.rows());
  const EdgeTopology t = edge_topology(F, nv);
  const Eigen::Index ne = t.E.rows();
  Eigen::MatrixXd out(nv + ne, 3); // separate buffer: V_out may alias V
  out.topRows(nv) = V;
  for (Eigen::Index e = 0; e < ne; ++e) out.row(nv + e) = 0.5 * (V.row(t.E(e, 0)) + V.row(t.E(e, 1)));
  Eigen::MatrixXi faces(4 * F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    // FE(f, k) is the edge opposite corner k: m_bc opposite a, m_ca opposite b, m_ab opposite c.
    const int m_bc = nv + t.FE(f, 0), m_ca = nv + t.FE(f, 1), m_ab = nv + t.FE(f, 2);
    faces.row(4 * f + 0) << a, m_ab, m_ca;
    faces.row(4 * f + 1) << b, m_bc, m_ab;
    faces.row(4 * f + 2) << c, m_ca, m_bc;
    faces.row(4 * f + 3) << m_ab, m_bc, m_ca;
  }
  V_out = std::move(out);
  F_out = std::move(faces);
}

void subdivide_midpoint(Eigen::MatrixXd& V, Eigen::MatrixXi& F, int times) {
  for (int k = 0; k < times; ++k) {
    Eigen::MatrixXd V_out;
    Eigen::MatrixXi F_out;
    subdivide_midpoint(V, F, V_out, F_out);
    V = std::move(V_out);
    F = std::move(F_out);
  }
}

} // namespace iarap
