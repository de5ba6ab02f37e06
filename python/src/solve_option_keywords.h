// The solve options (iarap/solver/solve_option_fields.h) as Python keywords of ARAP.solve and Simulation:
// named, typed, defaulted and documented from the schema, and read back into ArapSolveOptions with the
// library's checks and messages.
#pragma once
#include "keyword_signature.h"
#include "numpy_arrays.h"

#include "iarap/solver/arap_types.h"

#include <string>
#include <type_traits>
#include <vector>

namespace iarap::python {

// One parameter per solve option, in the schema's order, defaults from `defaults`; the first `positional`
// may be given by position, the others are keyword-only.
std::vector<Parameter> solve_option_parameters(const ArapSolveOptions& defaults, std::size_t positional);

// One docstring line per option: "tolerance: <doc> (<range>)".
std::string solve_option_docs();

// Sets every option of `options` from the arguments of the same names (a signature holding
// solve_option_parameters). Raises InputError (ValueError) with solve_option_error's message for a value of
// the wrong type or out of range.
void set_solve_options(ArapSolveOptions& options, const BoundArguments& arguments);

// iarap.SOLVE_OPTIONS: a dict per option (name, flag, kind, range, unit, doc, default of ARAP.solve), for
// iarap.batch's manifests and the parity test of docs/options.md.
py::tuple solve_option_table();

// A report field's value for Python: per-iteration lists as numpy arrays (flags such as `accepted` as bool),
// anything else as pybind11 casts it.
template <typename Value> py::object report_value(const Value& value) {
  if constexpr (std::is_same_v<Value, std::vector<double>>) {
    return to_numpy(value);
  } else if constexpr (std::is_same_v<Value, std::vector<unsigned char>>) {
    py::array_t<bool> flags(static_cast<py::ssize_t>(value.size()));
    for (std::size_t k = 0; k < value.size(); ++k)
      flags.mutable_at(static_cast<py::ssize_t>(k)) = value[k] != 0;
    return std::move(flags);
  } else {
    return py::cast(value);
  }
}

// ARAP.report: every field of visit_arap_report (report_value of each).
py::dict arap_report_dict(const ArapReport& report);

} // namespace iarap::python
