// JSON form of a ParamReport (`iarap param --json` and the viewer's POST /api/param).
#pragma once
#include "iarap/param/arap_parameterize.h"

#include <nlohmann/json.hpp>

namespace iarap::cli {

// Every field of visit_param_report: distortion ranges as {"min", "median", "max"} (max null where a
// triangle's sigma2 = 0: JSON has no infinity), per-iteration lists as arrays.
nlohmann::json param_report_json(const ParamReport& report);

} // namespace iarap::cli
