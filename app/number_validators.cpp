#include "number_validators.h"

#include <cmath>
#include <string>

namespace iarap::cli {

const CLI::Validator finite_non_negative(
    [](const std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
      if (!std::isfinite(value) || value < 0) return "'" + text + "' must be a finite number >= 0";
      return {};
    },
    "NUMBER >= 0");

const CLI::Validator finite_positive(
    [](const std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
      if (!std::isfinite(value) || !(value > 0)) return "'" + text + "' must be a finite number > 0";
      return {};
    },
    "NUMBER > 0");

const CLI::Validator finite_number(
    [](const std::string& text) -> std::string {
      double value = 0;
      if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
      if (!std::isfinite(value)) return "'" + text + "' must be a finite number";
      return {};
    },
    "NUMBER");

} // namespace iarap::cli
