#include "iarap/mesh/repair.h"

#include "face_index_range.h"
#include "iarap/core/errors.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/validate.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numeric>

namespace iarap {

RepairResult repair_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const RepairOptions& options) {
  if (V.cols() != 3)
    throw InputError("repair_mesh: V has " + std::to_string(V.cols()) + " columns; 3 needed");
  if (F.cols() != 3)
    throw InputError("repair_mesh: F has " + std::to_string(F.cols()) + " columns; 3 needed");
  const int nv = static_cast<int>(V.rows()), nf = static_cast<int>(F.rows());
  require_face_indices_in_range(F, nv, "repair_mesh: ");
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
