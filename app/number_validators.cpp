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

} // namespace iarap::cli
