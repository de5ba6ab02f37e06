// The schema of the solve options (solve_option_fields.h) and of the report (solve_report_fields.h): names,
// defaults read from ArapSolveOptions, ranges and the one message of a bad value.
#include "iarap/core/errors.h"
#include "iarap/solver/solve_option_fields.h"
#include "iarap/solver/solve_report_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <type_traits>

namespace iarap {
namespace {

std::string message_of(const ArapSolveOptions& options) {
  try {
    check_solve_options(options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string message_of_text(const std::string& name, const std::string& text) {
  ArapSolveOptions options;
  try {
    set_solve_option(options, name, text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SolveOptionFields, NamesAndFlagsAreDistinctAndDefaultsAreValid) {
  std::set<std::string> names, flags;
  ArapSolveOptions defaults;
  visit_solve_option_fields(defaults, [&](const SolveOptionField& field, const auto&) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_TRUE(flags.insert(field.flag).second) << field.flag;
    EXPECT_EQ(std::string(field.flag).rfind("--", 0), 0u) << field.flag;
    EXPECT_FALSE(std::string(field.doc).empty()) << field.name;
  });
  for (const char* name :
       {"iterations", "tolerance", "accelerator", "window", "gradient_tolerance", "time_budget_ms"})
    EXPECT_EQ(names.count(name), 1u) << name;
  EXPECT_NO_THROW(check_solve_options(defaults));
}

// The visitor hands out the members themselves: what a front-end writes through it is what arap_solve reads.
TEST(SolveOptionFields, VisitorWritesTheMembersOfArapSolveOptions) {
  ArapSolveOptions options;
  set_solve_option(options, "iterations", "7");
  set_solve_option(options, "tolerance", "-1");
  set_solve_option(options, "accelerator", "anderson");
  set_solve_option(options, "window", "3");
  set_solve_option(options, "gradient_tolerance", "1e-9");
  set_solve_option(options, "time_budget_ms", "12.5");
  EXPECT_EQ(options.max_iterations, 7);
  EXPECT_EQ(options.tolerance, -1.0); // negative: the energy rule is off, a valid choice
  EXPECT_EQ(options.accelerator, ArapAccelerator::Anderson);
  EXPECT_EQ(options.window, 3);
  EXPECT_EQ(options.gradient_tolerance, 1e-9);
  EXPECT_EQ(options.time_budget_ms, 12.5);
  EXPECT_NO_THROW(check_solve_options(options));
}

TEST(SolveOptionFields, OneMessageNamesTheOptionItsRangeAndTheValue) {
  ArapSolveOptions options;
  options.tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of(options), "tolerance must be a finite number; got nan");
  options = {};
  options.tolerance = std::numeric_limits<double>::infinity();
  EXPECT_EQ(message_of(options), "tolerance must be a finite number; got inf");
  options = {};
  options.gradient_tolerance = -2;
  EXPECT_EQ(message_of(options), "gradient_tolerance must be a finite number >= 0; got -2");
  options = {};
  options.max_iterations = -1;
  EXPECT_EQ(message_of(options), "iterations must be an integer in [0, 1000000]; got -1");
  options = {};
  options.window = 1001;
  EXPECT_EQ(message_of(options), "window must be an integer in [0, 1000]; got 1001");
  options = {};
  options.time_budget_ms = -0.5;
  EXPECT_EQ(message_of(options), "time_budget_ms must be a finite number >= 0; got -0.5");
  // Text goes through the same message, whatever the reason it is refused.
  EXPECT_EQ(message_of_text("tolerance", "nan"), "tolerance must be a finite number; got nan");
  EXPECT_EQ(message_of_text("iterations", "2.5"), "iterations must be an integer in [0, 1000000]; got 2.5");
  EXPECT_EQ(message_of_text("iterations", "99999999999"),
            "iterations must be an integer in [0, 1000000]; got 99999999999");
  EXPECT_EQ(message_of_text("window", ""), "window must be an integer in [0, 1000]; got nothing");
  EXPECT_EQ(message_of_text("gradient_tolerance", "1e-6x"),
            "gradient_tolerance must be a finite number >= 0; got 1e-6x");
  EXPECT_EQ(message_of_text("accelerator", "fast"),
            "accelerator must be one of newton, hybrid, lbfgs, anderson, none; got fast");
  EXPECT_EQ(
      message_of_text("max_iterations", "5")
          .rfind("unknown solve option 'max_iterations'; the options are iterations, tolerance, accelerator, "
                 "window, gradient_tolerance, time_budget_ms",
                 0),
      0u);
}

// Every value the ranges admit at their ends is admitted, and the next one out is not.
TEST(SolveOptionFields, RangesIncludeTheirEnds) {
  ArapSolveOptions options;
  visit_solve_option_fields(options, [&](const SolveOptionField& field, auto& value) {
    using Value = std::decay_t<decltype(value)>;
    if constexpr (!std::is_same_v<Value, ArapAccelerator>) {
      const Value kept = value;
      for (const double end : {field.low, field.high}) {
        if (!std::isfinite(end)) continue;
        value = static_cast<Value>(end);
        EXPECT_NO_THROW(check_solve_options(options)) << field.name << " = " << end;
        value = static_cast<Value>(end == field.low ? end - 1 : end + 1);
        EXPECT_THROW(check_solve_options(options), InputError) << field.name;
      }
      value = kept;
    }
  });
}

// A front-end solving on the mesh divided by s divides the options measured in mesh units by s, and only
// those.
TEST(SolveOptionFields, ScaleLengthOptionsDividesOnlyLengths) {
  ArapSolveOptions options;
  for (const char* name : {"tolerance", "gradient_tolerance", "time_budget_ms"})
    set_solve_option(options, name, "0.5");
  ArapSolveOptions scaled = options;
  scale_length_options(scaled, 8.0);
  visit_solve_option_fields(options, [&](const SolveOptionField& field, const auto& value) {
    visit_solve_option_fields(scaled, [&](const SolveOptionField& other, const auto& after) {
      using Value = std::decay_t<decltype(value)>;
      if constexpr (std::is_same_v<Value, std::decay_t<decltype(after)>>) {
        if (&field != &other) return;
        const bool length = std::string(field.unit) == solve_option::mesh_units;
        if constexpr (std::is_same_v<Value, double>) {
          EXPECT_EQ(after, length ? value / 8.0 : value) << field.name;
        } else {
          EXPECT_FALSE(length) << field.name << ": only numbers can be lengths";
          EXPECT_EQ(after, value) << field.name;
        }
      }
    });
  });
}

// Each field of a report whose values all differ comes back once, under its own name.
TEST(SolveReportFields, EveryFieldOnceByName) {
  ArapReport report;
  report.iterations = 2;
  report.converged = true;
  report.stop_reason = ArapStopReason::GradientTolerance;
  report.energies = {3.0, 2.0};
  report.accepted = {0, 1};
  report.accelerator = ArapAccelerator::Lbfgs;
  report.newton_trust_radius = 0.25;
  std::set<std::string> names;
  int count = 0;
  visit_arap_report(report, [&](const char* name, const auto& value) {
    ++count;
    names.insert(name);
    using Value = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<Value, std::string>) {
      const std::string expected = std::string(name) == "stop_reason" ? "gradient_tolerance" : "lbfgs";
      EXPECT_EQ(value, expected) << name;
    } else if constexpr (std::is_same_v<Value, std::vector<double>>) {
      if (std::string(name) == "energies") {
        EXPECT_EQ(value, report.energies);
      }
    }
  });
  EXPECT_EQ(static_cast<int>(names.size()), count);
  for (const char* name : {"iterations", "converged", "stop_reason", "energies", "accepted", "accelerator",
                           "newton_trust_radius", "newton_reference_gradient", "elapsed_ms", "solves"})
    EXPECT_EQ(names.count(name), 1u) << name;
}

} // namespace
} // namespace iarap
