// arap_parameterize on a disk already prepared: what uv_atlas calls for its charts, which it builds as
// disks and has already checked, and whose LSCM start it computes first (to split a chart whose start
// crosses itself before the solve).
#pragma once
#include "iarap/core/stopwatch.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/disk_mesh.h"

namespace iarap::param_detail {

// arap_parameterize(V, F, options) for disk = prepare_disk(V / s, F) (or disk_of_chart): UV and energies
// in V's units; the report's times counted from total_start.
ParamResult arap_parameterize_disk(const DiskMesh& disk, double s, const ParamOptions& options,
                                   Clock::time_point total_start);

} // namespace iarap::param_detail
