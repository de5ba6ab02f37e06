// JSON form of a ParamReport (`iarap param --json` and the viewer's POST /api/param).
#pragma once
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/uv_atlas.h"

#include <nlohmann/json.hpp>

namespace iarap::cli {

// Every field of visit_param_report: distortion ranges as {"min", "median", "max"} (max null where a
// triangle's sigma2 = 0: JSON has no infinity), per-iteration lists as arrays.
nlohmann::json param_report_json(const ParamReport& report);

// The atlas's options and report (`iarap param --json` on an atlas and POST /api/param's header), added to j:
// the energy and packing options, "charts" (the count), "chart_list" (per chart) and the overall fields.
void add_atlas_report_json(nlohmann::json& j, const AtlasOptions& options, const AtlasReport& report);

} // namespace iarap::cli
