// Carries a scenario over to a mesh whose vertices were renumbered (e.g. by repair_mesh), so that it is
// resolved on the repaired mesh: its slabs, boxes and spheres then select only vertices that stay, never
// an unreferenced vertex of a scan that the repair drops.
#pragma once
#include "iarap/scene/scenario.h"

namespace iarap {

// old_to_new(i) is the new index of old vertex i, or -1 when it was removed. Index regions are renumbered
// (and deduplicated where vertices were merged); geometric regions are kept as they are. Throws
// InputError naming the region's path and the old index when an index is out of range or was removed.
Scenario remap_scenario(const Scenario& scenario, const Eigen::VectorXi& old_to_new);

} // namespace iarap
