// The user-facing options of arap_solve (ArapSolveOptions) as one list of named fields. Every front-end
// is built from it: the flags of `iarap deform` and `iarap simulate`, the keywords of ARAP.solve and
// iarap.Simulation, the JSON fields of `iarap serve`, the manifest fields of iarap.batch and the table of
// docs/options.md; so a name, a range, a default or an error message is written once. Defaults are never
// written here: they are read from a default-constructed ArapSolveOptions (or the caller's own defaults,
// e.g. SimulationOptions::default_step_options()). Callbacks, forces and Newton's warm state are not
// options a user types and stay out of the list.
#pragma once
#include "iarap/solver/arap_types.h"

#include <limits>
#include <string>

namespace iarap {

enum class SolveOptionKind {
  Integer, // an int in [low, high]
  Number,  // a finite double in [low, high]
  Choice,  // a name among solve_option_choices (the accelerator)
};

struct SolveOptionField {
  const char* name; // canonical: Python keyword, HTTP JSON field, manifest field, docs
  const char* flag; // the command-line flag (deform, simulate)
  SolveOptionKind kind;
  double low, high; // inclusive range of Integer and Number (+-infinity: unbounded); unused by Choice
  const char* unit; // "" for a plain count or a ratio
  const char* doc;  // one line, for --help, docstrings and docs/options.md
};

namespace solve_option {
inline constexpr double unbounded = std::numeric_limits<double>::infinity();
// The unit of options measured like the mesh's coordinates (see scale_length_options).
inline constexpr const char* mesh_units = "mesh units";
inline constexpr SolveOptionField iterations{"iterations",
                                             "--iterations",
                                             SolveOptionKind::Integer,
                                             0,
                                             1000000,
                                             "iterations",
                                             "At most this many local/global iterations"};
// A negative tolerance turns the energy rule off (exactly `iterations` iterations): kept valid.
inline constexpr SolveOptionField tolerance{
    "tolerance",
    "--tolerance",
    SolveOptionKind::Number,
    -unbounded,
    unbounded,
    "",
    "Stop when one iteration lowers the energy by at most this fraction of itself (negative: never)"};
inline constexpr SolveOptionField accelerator{
    "accelerator",
    "--accel",
    SolveOptionKind::Choice,
    0,
    0,
    "",
    "Accelerator of the local/global iteration: newton, hybrid (L-BFGS, then Newton once it stalls), "
    "lbfgs, anderson or none"};
inline constexpr SolveOptionField window{
    "window",
    "--window",
    SolveOptionKind::Integer,
    0,
    1000,
    "",
    "History length of the accelerator (newton: conjugate-gradient steps per Newton step; hybrid: both; 0: "
    "plain)"};
inline constexpr SolveOptionField gradient_tolerance{
    "gradient_tolerance",
    "--grad-tol",
    SolveOptionKind::Number,
    0,
    unbounded,
    "",
    "Also stop when the gradient norm at the free vertices falls to this fraction of its initial value "
    "(0: off)"};
inline constexpr SolveOptionField time_budget_ms{
    "time_budget_ms",
    "--time-budget",
    SolveOptionKind::Number,
    0,
    unbounded,
    "ms",
    "Stop after the iteration that ends past this many milliseconds of solving (0: none)"};
// Newton's trust radius is state a solve hands on (ArapReport::newton_trust_radius): as an option it starts
// a solve that continues another where that one ended; its reference gradient stays internal.
inline constexpr SolveOptionField newton_trust_radius{
    "newton_trust_radius",
    "--trust-radius",
    SolveOptionKind::Number,
    0,
    unbounded,
    mesh_units,
    "Newton's initial trust radius, the L_ff norm of a step (0: the first plain step's length; a report's "
    "newton_trust_radius continues that solve)"};
// A ratio: ALPHA multiplies the rest area, so it does not change with the mesh's scale.
inline constexpr SolveOptionField rotation_smoothing{
    "rotation_smoothing",
    "--rotation-smoothing",
    SolveOptionKind::Number,
    0,
    unbounded,
    "",
    "Rotation smoothing ALPHA (CGAL's SRE_ARAP alpha, symmetric form; docs/smoothing.md): neighbouring "
    "cells' "
    "rotations are pulled together (0: off)"};
} // namespace solve_option

// Calls visit(field, value) for each user-facing option of `options`, in a fixed order; value is an int&,
// double& or ArapAccelerator& (a const reference for a const `options`). The single place that pairs a
// field with its member of ArapSolveOptions.
template <typename Options, typename Visitor>
void visit_solve_option_fields(Options& options, Visitor&& visit) {
  visit(solve_option::iterations, options.max_iterations);
  visit(solve_option::tolerance, options.tolerance);
  visit(solve_option::accelerator, options.accelerator);
  visit(solve_option::window, options.window);
  visit(solve_option::gradient_tolerance, options.gradient_tolerance);
  visit(solve_option::time_budget_ms, options.time_budget_ms);
  visit(solve_option::newton_trust_radius, options.newton_trust_radius);
  visit(solve_option::rotation_smoothing, options.rotation_smoothing);
}

// The names a Choice field accepts, comma-separated ("newton, hybrid, lbfgs, anderson, none").
std::string solve_option_choices(const SolveOptionField& field);

// What a field accepts, in words: "an integer in [0, 1000]", "a finite number >= 0", "a finite number",
// "one of newton, hybrid, lbfgs, anderson, none".
std::string solve_option_range(const SolveOptionField& field);

// The one message of a bad value, whatever the front-end: "tolerance must be a finite number; got nan".
// `got` is the value as the user wrote it (or as solve_option_value_text formats it).
std::string solve_option_error(const SolveOptionField& field, const std::string& got);

// A value as the messages, --help and the docs show it: integers in full, numbers as "1e-06", "0.5", "nan",
// choices by name.
std::string solve_option_value_text(double value);
std::string solve_option_value_text(int value);
std::string solve_option_value_text(ArapAccelerator value);

// Divides every option measured in mesh units by `scale` (> 0): for a front-end that takes the options in
// the file's units and solves on the mesh divided by scale (`iarap deform`, `iarap simulate`:
// normalize_scale.h).
void scale_length_options(ArapSolveOptions& options, double scale);

// Throws InputError (solve_option_error) for the first field of `options` out of its range.
void check_solve_options(const ArapSolveOptions& options);

// Sets the field named `name` of `options` from text (a command-line or manifest value): an integer, a
// number or a choice's name, then checked against its range. Throws InputError (solve_option_error) for
// text that is not such a value or out of range, and for an unknown name (listing the known ones).
void set_solve_option(ArapSolveOptions& options, const std::string& name, const std::string& text);

} // namespace iarap
