#include "solve_report_json.h"

#include "iarap/solver/solve_option_fields.h"
#include "iarap/solver/solve_report_fields.h"

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

} // namespace iarap::cli
