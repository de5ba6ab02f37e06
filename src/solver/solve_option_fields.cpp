#include "iarap/solver/solve_option_fields.h"

#include "iarap/core/errors.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <string_view>
#include <type_traits>

namespace iarap {
namespace {

constexpr std::array<ArapAccelerator, 5> accelerators = {ArapAccelerator::Newton, ArapAccelerator::Hybrid,
                                                         ArapAccelerator::Lbfgs, ArapAccelerator::Anderson,
                                                         ArapAccelerator::None};

bool in_range(const SolveOptionField& field, double value) {
  return value >= field.low && value <= field.high &&
         (field.kind != SolveOptionKind::Number || std::isfinite(value));
}

// The whole of `text` as a number (strtod: "1e-6", "nan", "inf"); false for anything else or nothing.
bool parse_number(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

// The whole of `text` as a decimal int; false for anything else (a fraction, an exponent, an overflow).
bool parse_integer(const std::string& text, int& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE || parsed < std::numeric_limits<int>::min() ||
      parsed > std::numeric_limits<int>::max())
    return false;
  value = static_cast<int>(parsed);
  return true;
}

} // namespace

std::string solve_option_choices(const SolveOptionField& field) {
  if (field.kind != SolveOptionKind::Choice) return {};
  std::string names;
  for (const ArapAccelerator a : accelerators)
    names += (names.empty() ? "" : ", ") + arap_accelerator_name(a);
  return names;
}

std::string solve_option_range(const SolveOptionField& field) {
  switch (field.kind) {
  case SolveOptionKind::Choice:
    return "one of " + solve_option_choices(field);
  case SolveOptionKind::Integer:
    return "an integer in [" + solve_option_value_text(field.low) + ", " +
           solve_option_value_text(field.high) + "]";
  case SolveOptionKind::Number:
    break;
  }
  const bool low = std::isfinite(field.low), high = std::isfinite(field.high);
  if (low && high)
    return "a finite number in [" + solve_option_value_text(field.low) + ", " +
           solve_option_value_text(field.high) + "]";
  if (low) return "a finite number >= " + solve_option_value_text(field.low);
  if (high) return "a finite number <= " + solve_option_value_text(field.high);
  return "a finite number";
}

std::string solve_option_error(const SolveOptionField& field, const std::string& got) {
  return std::string(field.name) + " must be " + solve_option_range(field) + "; got " + got;
}

std::string solve_option_value_text(double value) {
  std::ostringstream text;
  text << std::setprecision(15) << value; // 1000000 in full, 1e-06 short
  return text.str();
}

std::string solve_option_value_text(int value) {
  return std::to_string(value);
}

std::string solve_option_value_text(ArapAccelerator value) {
  return arap_accelerator_name(value);
}

void scale_length_options(ArapSolveOptions& options, double scale) {
  visit_solve_option_fields(options, [scale](const SolveOptionField& field, auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, double>) {
      if (std::string_view(field.unit) == solve_option::mesh_units) value /= scale;
    }
  });
}

void check_solve_options(const ArapSolveOptions& options) {
  visit_solve_option_fields(options, [](const SolveOptionField& field, const auto& value) {
    if constexpr (!std::is_same_v<std::decay_t<decltype(value)>, ArapAccelerator>) {
      if (!in_range(field, static_cast<double>(value)))
        throw InputError(solve_option_error(field, solve_option_value_text(value)));
    }
  });
}

void set_solve_option(ArapSolveOptions& options, const std::string& name, const std::string& text) {
  bool found = false;
  std::string known;
  visit_solve_option_fields(options, [&](const SolveOptionField& field, auto& value) {
    known += (known.empty() ? "" : ", ") + std::string(field.name);
    if (name != field.name) return;
    found = true;
    using Value = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<Value, ArapAccelerator>) {
      for (const ArapAccelerator a : accelerators)
        if (text == arap_accelerator_name(a)) {
          value = a;
          return;
        }
    } else if constexpr (std::is_same_v<Value, int>) {
      int parsed = 0;
      if (parse_integer(text, parsed) && in_range(field, parsed)) {
        value = parsed;
        return;
      }
    } else {
      double parsed = 0;
      if (parse_number(text, parsed) && in_range(field, parsed)) {
        value = parsed;
        return;
      }
    }
    throw InputError(solve_option_error(field, text.empty() ? "nothing" : text));
  });
  if (!found) throw InputError("unknown solve option '" + name + "'; the options are " + known);
}

} // namespace iarap
