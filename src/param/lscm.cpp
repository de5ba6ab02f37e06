#include "iarap/param/lscm.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"

#include "../solver/constrained_solve.h"

#include <cmath>
#include <string>
#include <utility>

namespace iarap {

namespace {

// Beyond this many boundary vertices the farthest pair is found by a double sweep instead of all pairs.
constexpr std::size_t exact_pair_limit = 4096;

double squared_distance(const DiskMesh& disk, int a, int b) {
  return (disk.V.row(a) - disk.V.row(b)).squaredNorm();
}

// The boundary vertex farthest from a.
int farthest_from(const DiskMesh& disk, int a) {
  int best = a;
  double best_d = -1;
  for (int v : disk.boundary) {
    const double d = squared_distance(disk, a, v);
    if (d > best_d) {
      best = v;
      best_d = d;
    }
  }
  return best;
}

std::pair<int, int> farthest_boundary_pair(const DiskMesh& disk) {
  const std::vector<int>& b = disk.boundary;
  if (b.size() > exact_pair_limit) {
    const int a = farthest_from(disk, b.front());
    return {a, farthest_from(disk, a)};
  }
  std::pair<int, int> best{b[0], b[1]};
  double best_d = -1;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (std::size_t j = i + 1; j < b.size(); ++j) {
      const double d = squared_distance(disk, b[i], b[j]);
      if (d > best_d) {
        best = {b[i], b[j]};
        best_d = d;
      }
    }
  return best;
}

// The conformal energy's matrix over the unknowns (u_0..u_{n-1}, v_0..v_{n-1}). Per face
// area_f ((a - d)^2 + (b + c)^2) = area_f (||J_f||^2 - 2 det J_f), and summed over the faces
// sum_f area_f ||J_f||^2 = u^T L u + v^T L v (L the cotan Laplacian) while sum_f area_f det J_f is the
// signed area of the map, (1/2) sum (u_i v_j - u_j v_i) over the boundary edges i -> j (the interior
// edges cancel). So Q = [L -M; -M^T L] with M non-zero on boundary edges only: u and v couple through the
// boundary alone, and the factor is about twice L's instead of the four times a per-face 6 x 6 assembly
// (every edge coupling u and v, in entries that cancel) would give.
Eigen::SparseMatrix<double> conformal_energy_matrix(const DiskMesh& disk) {
  const auto n = static_cast<int>(disk.V.rows());
  const Eigen::SparseMatrix<double> L = cotan_laplacian(disk.V, disk.F);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(2 * L.nonZeros()) + 4 * disk.boundary.size());
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      triplets.emplace_back(it.row(), col, it.value());
      triplets.emplace_back(n + it.row(), n + col, it.value());
    }
  // -2 x area = sum over boundary edges i -> j of (u_j v_i - u_i v_j).
  const std::vector<int>& b = disk.boundary;
  for (std::size_t p = 0; p < b.size(); ++p) {
    const int i = b[p], j = b[(p + 1) % b.size()];
    triplets.emplace_back(i, n + j, -0.5);
    triplets.emplace_back(n + j, i, -0.5);
    triplets.emplace_back(j, n + i, 0.5);
    triplets.emplace_back(n + i, j, 0.5);
  }
  Eigen::SparseMatrix<double> Q(2 * n, 2 * n);
  Q.setFromTriplets(triplets.begin(), triplets.end());
  return Q;
}

} // namespace

UvPins lscm_pins(const DiskMesh& disk) {
  const auto [a, b] = farthest_boundary_pair(disk);
  UvPins pins;
  pins.vertices.resize(2);
  pins.vertices << a, b;
  pins.uv.resize(2, 2);
  pins.uv << 0, 0, std::sqrt(squared_distance(disk, a, b)), 0;
  return pins;
}

Eigen::MatrixXd lscm(const DiskMesh& disk, const UvPins& pins) {
  const auto n = static_cast<int>(disk.V.rows());
  check_uv_pins(pins, n);
  if (pins.size() < 2)
    throw InputError(
        "LSCM needs at least two pinned vertices (its energy is invariant to similarities); got " +
        std::to_string(pins.size()));
  std::vector<int> fixed;
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(2 * n, 1);
  for (Eigen::Index p = 0; p < pins.size(); ++p) {
    const int v = pins.vertices(p);
    fixed.push_back(v);
    fixed.push_back(n + v);
    x(v, 0) = pins.uv(p, 0);
    x(n + v, 0) = pins.uv(p, 1);
  }
  detail::solve_constrained(conformal_energy_matrix(disk), fixed, Eigen::MatrixXd::Zero(2 * n, 1), x,
                            "the LSCM system");
  Eigen::MatrixXd UV(n, 2);
  UV.col(0) = x.col(0).head(n);
  UV.col(1) = x.col(0).tail(n);
  return UV;
}

Eigen::MatrixXd lscm(const DiskMesh& disk) {
  return lscm(disk, lscm_pins(disk));
}

} // namespace iarap
