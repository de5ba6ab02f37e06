// The soft constraints of deform and simulate: the library's conversions (iarap/jobs/soft_constraints.h)
// under the tool's namespace.
#pragma once
#include "iarap/jobs/soft_constraints.h"

namespace iarap::cli {

using iarap::hard_point_conflict_message;
using iarap::soft_constraints_of;
using iarap::soft_targets_of;

} // namespace iarap::cli
