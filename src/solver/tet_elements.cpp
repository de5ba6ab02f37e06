#include "iarap/core/errors.h"
#include "iarap/io/tet_mesh.h"
#include "iarap/solver/arap_tets.h"

#include "traced_elements.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap {

namespace {

// The six edges (i, j) of a tetrahedron's corners and the edge (k, l) opposite each.
constexpr int tet_edge[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2},
                                {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

} // namespace

ArapElements tet_arap_elements(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  if (V.cols() != 3)
    throw InputError("tet ARAP: V must be #V x 3, got " + std::to_string(V.cols()) + " columns");
  if (T.cols() != 4)
    throw InputError("tet ARAP: T must be #T x 4, got " + std::to_string(T.cols()) + " columns");
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!V.row(v).allFinite())
      throw InputError("tet ARAP: vertex " + std::to_string(v) + " has a non-finite coordinate");
  const TetProblem problem = find_tet_problem(V, T);
  if (problem.tet >= 0) {
    const std::string message = "tet ARAP: " + problem.message;
    if (message.find("zero volume") != std::string::npos) throw TopologyError(message);
    throw InputError(message);
  }
  const int n = static_cast<int>(V.rows());
  const Eigen::Index m = 6 * T.rows();
  ArapElements el;
  el.num_vertices = n;
  el.num_cells = std::max(static_cast<int>(T.rows()), n);
  el.b_index.resize(m, 3);
  el.b_value.resize(m, 3);
  el.w.resize(m);
  el.face.assign(static_cast<size_t>(m), -1);
  el.cell_start.resize(static_cast<size_t>(m) + 1);
  el.cell.resize(static_cast<size_t>(m));
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const auto corner = [&](int c) -> Eigen::Vector3d { return V.row(T(t, c)).transpose(); };
    const Eigen::Vector3d a = corner(0);
    const double volume = std::abs((corner(1) - a).dot((corner(2) - a).cross(corner(3) - a))) / 6.0;
    for (int k = 0; k < 6; ++k) {
      const Eigen::Index e = 6 * t + k;
      const int* c = tet_edge[k];
      // l_kl cot(theta_kl) = (x × u) . (x × v) / (6 vol) with x = V_l - V_k, u = V_i - V_k, v = V_j - V_k.
      const Eigen::Vector3d x = corner(c[3]) - corner(c[2]);
      const double l_cot =
          x.cross(corner(c[0]) - corner(c[2])).dot(x.cross(corner(c[1]) - corner(c[2]))) / (6.0 * volume);
      el.b_index.row(e) << T(t, c[0]), T(t, c[1]), T(t, c[0]);
      el.b_value.row(e) << -1.0, 1.0, 0.0;
      el.w(e) = 2.0 * l_cot / 6.0; // w / 2 = c_ij
      el.cell_start[static_cast<size_t>(e)] = static_cast<int>(e);
      el.cell[static_cast<size_t>(e)] = static_cast<int>(t);
    }
  }
  el.cell_start[static_cast<size_t>(m)] = static_cast<int>(m);
  detail::finish_elements(V, el);
  return el;
}

} // namespace iarap
