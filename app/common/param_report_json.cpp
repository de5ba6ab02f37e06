#include "param_report_json.h"

#include "iarap/param/param_report_fields.h"

#include <type_traits>

namespace iarap::cli {

nlohmann::json param_report_json(const ParamReport& report) {
  nlohmann::json j;
  visit_param_report(report, [&j](const char* name, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, DistortionRange>)
      j[name] = {{"min", value.min}, {"median", value.median}, {"max", value.max}};
    else
      j[name] = value;
  });
  return j;
}

} // namespace iarap::cli
