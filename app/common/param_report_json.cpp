#include "param_report_json.h"

#include "iarap/param/atlas_report_fields.h"
#include "iarap/param/param_options.h"
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

void add_atlas_report_json(nlohmann::json& j, const AtlasOptions& options, const AtlasReport& report) {
  j["energy_kind"] = param_energy_name(options.param.energy);
  j["allow_flips"] = options.param.allow_flips;
  j["texture_size"] = options.texture_size;
  j["padding"] = options.padding;
  j["max_angle"] = options.max_normal_angle;
  j["target_distortion"] = options.target_distortion;
  j["min_chart_faces"] = options.min_chart_faces;
  j["tolerance"] = options.param.solve.tolerance;
  j["charts"] = report.charts.size();
  nlohmann::json charts = nlohmann::json::array();
  for (const AtlasChart& chart : report.charts) {
    nlohmann::json c;
    visit_atlas_chart(chart, [&c](const char* name, const auto& value) { c[name] = value; });
    charts.push_back(c);
  }
  j["chart_list"] = charts;
  visit_atlas_report(report, [&j](const char* name, const auto& value) { j[name] = value; });
}

} // namespace iarap::cli
