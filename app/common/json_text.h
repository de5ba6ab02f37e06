// JSON output of the tool as text. Paths come from the command line and need not be valid UTF-8 (Linux
// file names are bytes); nlohmann's default dump throws on them, after the work was done. Invalid bytes
// become U+FFFD instead, so the report is always written.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace iarap::cli {

inline std::string json_text(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

} // namespace iarap::cli
