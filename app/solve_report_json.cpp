#include "solve_report_json.h"

#include "iarap/core/resident_memory.h"
#include "iarap/solver/arap_memory.h"
#include "iarap/solver/solve_option_fields.h"
#include "iarap/solver/solve_report_fields.h"

#include <algorithm>
#include <type_traits>

namespace iarap::cli {

nlohmann::json solve_options_json(const ArapSolveOptions& options) {
  nlohmann::json j = nlohmann::json::object();
  visit_solve_option_fields(options, [&j](const SolveOptionField& field, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, ArapAccelerator>)
      j[field.name] = arap_accelerator_name(value);
    else
      j[field.name] = value;
  });
  return j;
}

void add_arap_report_json(const ArapReport& report, nlohmann::json& j) {
  visit_arap_report(report, [&j](const char* name, const auto& value) { j[name] = value; });
}

nlohmann::json memory_json(const ArapData& data) {
  nlohmann::json j;
  const ArapMemory memory = arap_memory(data);
  visit_arap_memory(memory, [&j](const char* name, std::size_t bytes) { j[name] = bytes; });
  j["bytes_per_vertex"] = data.V.rows() > 0 ? static_cast<double>(memory.total()) / data.V.rows() : 0.0;
  // Sampled apart (statm in pages, ru_maxrss in kilobytes): the peak is at least the resident set now.
  const std::size_t resident = current_resident_bytes();
  j["resident_bytes"] = resident;
  j["peak_resident_bytes"] = std::max(resident, peak_resident_bytes());
  return j;
}

} // namespace iarap::cli
