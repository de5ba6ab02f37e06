#include "iarap/scene/region.h"

#include "iarap/core/errors.h"

#include <algorithm>

namespace iarap {

BoundingBox bounding_box(const Eigen::MatrixXd& V) {
  BoundingBox box;
  bool any = false;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d p = V.row(i).transpose();
    if (!p.allFinite()) continue;
    box.min = any ? box.min.cwiseMin(p) : p;
    box.max = any ? box.max.cwiseMax(p) : p;
    any = true;
  }
  return box;
}

namespace {

// A point given in bounding-box coordinates, mapped to world coordinates.
Eigen::Vector3d from_box(const Eigen::Vector3d& u, const BoundingBox& box) {
  return box.min + u.cwiseProduct(box.max - box.min);
}

std::vector<int> select_by_rule(const Region& region, const Eigen::MatrixXd& V, const BoundingBox& box) {
  std::vector<int> selected;
  const auto n = static_cast<int>(V.rows());
  switch (region.kind) {
  case RegionKind::Indices:
    for (const int i : region.indices) {
      if (i < 0 || i >= n) {
        throw InputError(region.path + ": vertex index " + std::to_string(i) +
                         " out of range; the mesh has " + std::to_string(n) + " vertices");
      }
      selected.push_back(i);
    }
    break;
  case RegionKind::Bottom:
  case RegionKind::Top: {
    if (region.axis < 0 || region.axis > 2) throw InputError(region.path + ": axis must be 0, 1 or 2");
    if (!(region.fraction > 0 && region.fraction <= 1)) {
      throw InputError(region.path + ": fraction " + std::to_string(region.fraction) + " not in (0, 1]");
    }
    const int a = region.axis;
    const double extent = box.max(a) - box.min(a);
    const double bottom_limit = box.min(a) + region.fraction * extent;
    const double top_limit = box.max(a) - region.fraction * extent;
    for (int i = 0; i < n; ++i) {
      if (!V.row(i).allFinite()) continue; // a vertex with NaN/Inf has no place in any slab
      const double x = V(i, a);
      if (region.kind == RegionKind::Bottom ? x <= bottom_limit : x >= top_limit) selected.push_back(i);
    }
    break;
  }
  case RegionKind::Box: {
    const Eigen::Vector3d lo = region.relative ? from_box(region.lo, box) : region.lo;
    const Eigen::Vector3d hi = region.relative ? from_box(region.hi, box) : region.hi;
    if (!(lo.array() <= hi.array()).all())
      throw InputError(region.path + ": box min exceeds max on some axis");
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = V.row(i).transpose();
      if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) selected.push_back(i);
    }
    break;
  }
  case RegionKind::Sphere: {
    const Eigen::Vector3d c = region.relative ? from_box(region.center, box) : region.center;
    const double r = region.relative ? region.radius * box.diagonal() : region.radius;
    if (!(region.radius >= 0)) throw InputError(region.path + ": sphere radius must be >= 0");
    for (int i = 0; i < n; ++i) {
      if ((V.row(i).transpose() - c).stableNorm() <= r) // squares would overflow at 1e200
        selected.push_back(i);
    }
    break;
  }
  }
  return selected;
}

} // namespace

std::vector<int> select_region(const Region& region, const Eigen::MatrixXd& V, const BoundingBox& box) {
  std::vector<int> selected = select_by_rule(region, V, box);
  std::sort(selected.begin(), selected.end());
  selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  if (selected.empty()) throw InputError(region.path + ": selects no vertex");
  return selected;
}

} // namespace iarap
