// JSON form of the solve options and of an ArapReport (`iarap deform`'s report, `iarap simulate`'s
// options), both from the schemas of iarap/solver: solve_option_fields.h and solve_report_fields.h; and the
// memory a precomputation holds (arap_memory.h).
#pragma once
#include "iarap/solver/arap_types.h"

#include <nlohmann/json.hpp>

namespace iarap::cli {

// {"iterations": 50, "tolerance": 1e-06, "accelerator": "newton", ...}: every option by its canonical name.
nlohmann::json solve_options_json(const ArapSolveOptions& options);

// Every field of visit_arap_report into `j` (accepted as 0 / 1 per iteration).
void add_arap_report_json(const ArapReport& report, nlohmann::json& j);

// {"mesh": bytes, ..., "total": bytes, "bytes_per_vertex": ..., "resident_bytes": ...,
// "peak_resident_bytes": ...}: what data holds (arap_memory.h) and the process's resident set now and at
// its peak so far.
nlohmann::json memory_json(const ArapData& data);

} // namespace iarap::cli
