// Carries a constraint set over to a mesh whose vertices were renumbered (e.g. by repair_mesh).
#pragma once
#include "iarap/scene/constraint_set.h"

namespace iarap {

// old_to_new(i) is the new index of old vertex i, or -1 when it was removed. Vertices merged into
// one must agree on their targets. Throws InputError naming the old vertex index when a constrained
// vertex was removed, is out of old_to_new's range, or two merged vertices get different targets.
ConstraintSet remap_constraints(const ConstraintSet& constraints, const Eigen::VectorXi& old_to_new);

} // namespace iarap
