#include "iarap/scene/remap_scenario.h"

#include "iarap/core/errors.h"

#include <algorithm>

namespace iarap {
namespace {

void remap_regions(std::vector<Region>& regions, const Eigen::VectorXi& old_to_new) {
  for (Region& region : regions) {
    if (region.kind != RegionKind::Indices) continue;
    for (int& i : region.indices) {
      if (i < 0 || i >= old_to_new.size())
        throw InputError(region.path + ": vertex index " + std::to_string(i) +
                         " out of range; the mesh has " + std::to_string(old_to_new.size()) + " vertices");
      if (old_to_new(i) < 0)
        throw InputError(
            region.path + ": vertex " + std::to_string(i) +
            " is used by no face and was removed by mesh repair; select a vertex of the surface");
      i = old_to_new(i);
    }
    std::sort(region.indices.begin(), region.indices.end());
    region.indices.erase(std::unique(region.indices.begin(), region.indices.end()), region.indices.end());
  }
}

} // namespace

Scenario remap_scenario(const Scenario& scenario, const Eigen::VectorXi& old_to_new) {
  Scenario result = scenario;
  remap_regions(result.fixed, old_to_new);
  for (Handle& handle : result.handles) remap_regions(handle.vertices, old_to_new);
  return result;
}

} // namespace iarap
