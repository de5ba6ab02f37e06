// JSON form of the mesh checks that `iarap info` prints.
#pragma once
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/mesh/validate.h"

#include <nlohmann/json.hpp>

namespace iarap::cli {

// Every field of the report; genus is null where it is undefined.
nlohmann::json mesh_report_json(const MeshReport& report);

// flips, non_delaunay_before/after, mollify_delta, intrinsic_edges, segments, segments_per_edge (mean),
// max_segments_per_edge of an intrinsic Delaunay triangulation.
nlohmann::json intrinsic_summary_json(const IntrinsicDelaunay& intrinsic);

} // namespace iarap::cli
