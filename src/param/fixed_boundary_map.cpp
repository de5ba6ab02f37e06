#include "iarap/param/fixed_boundary_map.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"
#include "iarap/mesh/edge_topology.h"

#include "../solver/constrained_solve.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap {

namespace {

// The graph Laplacian of the mesh's edges (w_ij = 1), in cotan.h's sign convention.
Eigen::SparseMatrix<double> uniform_laplacian(const DiskMesh& disk) {
  const auto n = static_cast<int>(disk.V.rows());
  const EdgeTopology topology = edge_topology(disk.F, n);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(topology.E.rows()) * 4);
  for (Eigen::Index e = 0; e < topology.E.rows(); ++e) {
    const int i = topology.E(e, 0), j = topology.E(e, 1);
    triplets.emplace_back(i, j, -1.0);
    triplets.emplace_back(j, i, -1.0);
    triplets.emplace_back(i, i, 1.0);
    triplets.emplace_back(j, j, 1.0);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

} // namespace

Eigen::MatrixXd circle_boundary(const DiskMesh& disk) {
  const std::vector<int>& b = disk.boundary;
  const std::size_t m = b.size();
  std::vector<double> arc(m + 1, 0.0);
  for (std::size_t p = 0; p < m; ++p)
    arc[p + 1] = arc[p] + (disk.V.row(b[(p + 1) % m]) - disk.V.row(b[p])).norm();
  const double radius = std::sqrt(disk.area / M_PI);
  Eigen::MatrixXd uv(static_cast<Eigen::Index>(m), 2);
  for (std::size_t p = 0; p < m; ++p) {
    const double angle = 2 * M_PI * arc[p] / arc[m];
    uv.row(static_cast<Eigen::Index>(p)) << radius * std::cos(angle), radius * std::sin(angle);
  }
  return uv;
}

Eigen::MatrixXd fixed_boundary_map(const DiskMesh& disk, BoundaryMapWeights weights,
                                   const Eigen::MatrixXd& boundary_uv, const UvPins& inner_pins) {
  const auto m = static_cast<Eigen::Index>(disk.boundary.size());
  if (boundary_uv.rows() != m || boundary_uv.cols() != 2)
    throw InputError("boundary_uv must be #boundary x 2 = " + std::to_string(m) + " x 2; got " +
                     std::to_string(boundary_uv.rows()) + " x " + std::to_string(boundary_uv.cols()));
  if (!boundary_uv.allFinite()) throw InputError("boundary_uv must be finite");
  check_uv_pins(inner_pins, disk.V.rows());
  std::vector<int> fixed = disk.boundary;
  std::sort(fixed.begin(), fixed.end());
  for (Eigen::Index p = 0; p < inner_pins.size(); ++p) {
    const int v = inner_pins.vertices(p);
    if (std::binary_search(fixed.begin(), fixed.end(), v))
      throw InputError(
          "pin " + std::to_string(p) + " (vertex " + std::to_string(v) +
          ") is on the boundary, which this map puts on the circle: pin inner vertices only, or start "
          "from LSCM with a free boundary");
  }
  for (Eigen::Index p = 0; p < inner_pins.size(); ++p) fixed.push_back(inner_pins.vertices(p));
  const Eigen::SparseMatrix<double> L =
      weights == BoundaryMapWeights::Uniform ? uniform_laplacian(disk) : cotan_laplacian(disk.V, disk.F);
  Eigen::MatrixXd UV = Eigen::MatrixXd::Zero(disk.V.rows(), 2);
  for (Eigen::Index p = 0; p < m; ++p)
    UV.row(disk.boundary[static_cast<std::size_t>(p)]) = boundary_uv.row(p);
  for (Eigen::Index p = 0; p < inner_pins.size(); ++p) UV.row(inner_pins.vertices(p)) = inner_pins.uv.row(p);
  detail::solve_constrained(L, fixed, Eigen::MatrixXd::Zero(disk.V.rows(), 2), UV,
                            weights == BoundaryMapWeights::Uniform ? "the Tutte system"
                                                                   : "the harmonic system");
  return UV;
}

} // namespace iarap
