#include "iarap/mesh/repair.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/connected_components.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/validate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace iarap {

Eigen::VectorXi weld_representatives(const Eigen::MatrixXd& V, double tolerance) {
  const int n = static_cast<int>(V.rows());
  Eigen::VectorXi representative(n);
  std::iota(representative.data(), representative.data() + n, 0);
  if (n == 0 || V.cols() != 3) return representative;

  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(INFINITY);
  for (int v = 0; v < n; ++v)
    if (V.row(v).allFinite()) lo = lo.cwiseMin(V.row(v));
  // Cell size: the tolerance, so any two points within it lie in the same or adjacent cells. A zero tolerance
  // (identical positions only) still needs a positive cell, taken tiny relative to the coordinates.
  const double bbox = bounding_box_diagonal(V);
  const double cell = tolerance > 0 ? tolerance : std::max(bbox, 1.0) * 1e-15;
  // Copies of one position join first, by a sort of the positions, and only the first copy enters the
  // grid: the pair search below visits every pair within a cell neighbourhood, quadratic in a pile of 100K
  // copies of one point.
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v)
    if (V.row(v).allFinite()) order.push_back(v);
  const auto position_less = [&](int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (V(a, k) != V(b, k)) return V(a, k) < V(b, k);
    return a < b;
  };
  std::sort(order.begin(), order.end(), position_less);
  std::vector<int> pair_a, pair_b;
  std::vector<char> is_copy(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 1; i < order.size(); ++i)
    if (V.row(order[i]) == V.row(order[i - 1])) {
      pair_a.push_back(order[i - 1]);
      pair_b.push_back(order[i]);
      is_copy[static_cast<std::size_t>(order[i])] = 1;
    }

  using Key = std::array<std::int64_t, 4>; // cell x, y, z, vertex
  std::vector<Key> keys;
  keys.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    if (!V.row(v).allFinite() || is_copy[static_cast<std::size_t>(v)]) continue;
    Key key;
    for (int k = 0; k < 3; ++k) {
      // Offsets from the minimum are at most bbox / cell; clamp so absurd ratios cannot overflow.
      const double q = std::floor((V(v, k) - lo(k)) / cell);
      key[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(std::min(q, 4e18));
    }
    key[3] = v;
    keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end());
  for (const Key& key : keys) {
    const int i = static_cast<int>(key[3]);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const Key from{key[0] + dx, key[1] + dy, key[2] - 1, 0};
        const Key to{key[0] + dx, key[1] + dy, key[2] + 1, INT64_MAX};
        for (auto it = std::lower_bound(keys.begin(), keys.end(), from); it != keys.end() && *it <= to;
             ++it) {
          const int j = static_cast<int>((*it)[3]);
          if (j <= i) continue; // each pair once
          // Zero tolerance compares positions exactly (a norm of 1e-300 differences would underflow to 0).
          const bool close =
              tolerance > 0 ? (V.row(i) - V.row(j)).stableNorm() <= tolerance : V.row(i) == V.row(j);
          if (close) {
            pair_a.push_back(i);
            pair_b.push_back(j);
          }
        }
      }
  }
  if (pair_a.empty()) return representative;
  Eigen::MatrixXi pairs(static_cast<Eigen::Index>(pair_a.size()), 3);
  for (std::size_t p = 0; p < pair_a.size(); ++p)
    pairs.row(static_cast<Eigen::Index>(p)) << pair_a[p], pair_b[p], pair_b[p];
  int count = 0;
  const Eigen::VectorXi component = vertex_components(pairs, n, &count);
  // Components are numbered in order of their smallest vertex, so the first vertex met in each is its
  // smallest.
  std::vector<int> smallest(static_cast<std::size_t>(count), -1);
  for (int v = 0; v < n; ++v) {
    int& s = smallest[static_cast<std::size_t>(component(v))];
    if (s < 0) s = v;
    representative(v) = s;
  }
  return representative;
}

RepairResult repair_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RepairOptions& options) {
  if (V.cols() != 3)
    throw InputError("repair_mesh: V has " + std::to_string(V.cols()) + " columns; 3 needed");
  if (F.cols() != 3)
    throw InputError("repair_mesh: F has " + std::to_string(F.cols()) + " columns; 3 needed");
  const int nv = static_cast<int>(V.rows()), nf = static_cast<int>(F.rows());
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) < 0 || F(f, k) >= nv)
        throw InputError("repair_mesh: face " + std::to_string(f) + " uses vertex " +
                         std::to_string(F(f, k)) + "; mesh has " + std::to_string(nv) + " vertices");
  RepairResult result;
  // Tolerances and areas on V / s (exact for a power of two s), so that they hold at any scale.
  const Eigen::MatrixXd Vn = V / normalizing_scale(V);
  const double diagonal = bounding_box_diagonal(Vn);

  Eigen::VectorXi representative(nv);
  std::iota(representative.data(), representative.data() + nv, 0);
  if (options.weld) {
    representative = weld_representatives(Vn, options.weld_tolerance * diagonal);
    const int merged = static_cast<int>(
        (representative.array() != Eigen::VectorXi::LinSpaced(nv, 0, nv - 1).array()).count());
    if (merged > 0)
      result.actions.push_back("welded " + std::to_string(merged) +
                               " vertices onto coincident ones (tolerance " +
                               std::to_string(options.weld_tolerance) + " x bbox diagonal)");
  }

  std::vector<int> kept_faces;
  kept_faces.reserve(static_cast<std::size_t>(nf));
  int collapsed = 0, flat = 0;
  const double min_area = 1e-12 * diagonal * diagonal;
  for (int f = 0; f < nf; ++f) {
    const int a = representative(F(f, 0)), b = representative(F(f, 1)), c = representative(F(f, 2));
    const bool repeated_before = F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 0) == F(f, 2);
    if (!repeated_before && (a == b || b == c || a == c)) {
      ++collapsed;
      continue;
    }
    if (options.remove_zero_area && !repeated_before) {
      const Eigen::RowVector3d pa = Vn.row(a), pb = Vn.row(b), pc = Vn.row(c);
      const double area = 0.5 * (pb - pa).cross(pc - pa).norm();
      if (area <= min_area) {
        ++flat;
        continue;
      }
    }
    kept_faces.push_back(f);
  }
  if (collapsed > 0)
    result.actions.push_back("removed " + std::to_string(collapsed) + " faces that welding collapsed");
  if (flat > 0)
    result.actions.push_back("removed " + std::to_string(flat) +
                             " zero-area faces (area <= 1e-12 x bbox diagonal^2)");

  std::vector<char> used(static_cast<std::size_t>(nv), 0);
  for (int f : kept_faces)
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(representative(F(f, k)))] = 1;
  std::vector<int> new_index(static_cast<std::size_t>(nv), -1);
  int count = 0, unreferenced = 0;
  for (int v = 0; v < nv; ++v) {
    if (representative(v) != v) continue;
    if (options.remove_unreferenced && !used[static_cast<std::size_t>(v)]) {
      ++unreferenced;
      continue;
    }
    new_index[static_cast<std::size_t>(v)] = count++;
  }
  if (unreferenced > 0)
    result.actions.push_back("removed " + std::to_string(unreferenced) + " unreferenced vertices");

  result.old_to_new.resize(nv);
  result.V.resize(count, 3);
  for (int v = 0; v < nv; ++v) {
    result.old_to_new(v) = new_index[static_cast<std::size_t>(representative(v))];
    if (representative(v) == v && new_index[static_cast<std::size_t>(v)] >= 0)
      result.V.row(new_index[static_cast<std::size_t>(v)]) = V.row(v);
  }
  result.F.resize(static_cast<Eigen::Index>(kept_faces.size()), 3);
  for (std::size_t i = 0; i < kept_faces.size(); ++i)
    for (int k = 0; k < 3; ++k)
      result.F(static_cast<Eigen::Index>(i), k) = result.old_to_new(F(kept_faces[i], k));
  return result;
}

} // namespace iarap
