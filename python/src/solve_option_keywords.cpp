#include "solve_option_keywords.h"

#include "numpy_arrays.h"

#include "iarap/core/errors.h"
#include "iarap/solver/solve_option_fields.h"
#include "iarap/solver/solve_report_fields.h"

#include <pybind11/numpy.h>

#include <type_traits>

namespace iarap::python {
namespace {

template <typename Value> py::object python_value(const Value& value) {
  if constexpr (std::is_same_v<Value, ArapAccelerator>)
    return py::str(arap_accelerator_name(value));
  else
    return py::cast(value);
}

const char* annotation(const SolveOptionField& field) {
  switch (field.kind) {
  case SolveOptionKind::Integer:
    return "int";
  case SolveOptionKind::Number:
    return "float";
  case SolveOptionKind::Choice:
    break;
  }
  return "str";
}

} // namespace

std::vector<Parameter> solve_option_parameters(const ArapSolveOptions& defaults, std::size_t positional) {
  std::vector<Parameter> parameters;
  visit_solve_option_fields(defaults, [&](const SolveOptionField& field, const auto& value) {
    parameters.push_back(
        {field.name, annotation(field), python_value(value), parameters.size() >= positional});
  });
  return parameters;
}

std::string solve_option_docs() {
  const ArapSolveOptions library_defaults;
  std::string text;
  visit_solve_option_fields(library_defaults, [&](const SolveOptionField& field, const auto&) {
    text += std::string(field.name) + ": " + field.doc + " (" + solve_option_range(field) +
            (*field.unit ? std::string(", ") + field.unit : std::string()) + ").\n";
  });
  return text;
}

void set_solve_options(ArapSolveOptions& options, const BoundArguments& arguments) {
  visit_solve_option_fields(options, [&](const SolveOptionField& field, const auto&) {
    const py::object& value = arguments[field.name];
    // Numbers go through their text (Python's repr round-trips a float): one parser and one message for
    // the command line, the manifests and Python. A string is a choice's name, never a number.
    if (py::isinstance<py::str>(value) != (field.kind == SolveOptionKind::Choice))
      throw InputError(solve_option_error(field, py::repr(value).cast<std::string>()));
    set_solve_option(options, field.name, py::str(value).cast<std::string>());
  });
}

py::tuple solve_option_table() {
  const ArapSolveOptions library_defaults;
  py::list table;
  visit_solve_option_fields(library_defaults, [&](const SolveOptionField& field, const auto& value) {
    py::dict d;
    d["name"] = field.name;
    d["flag"] = field.flag;
    d["kind"] = annotation(field);
    d["range"] = solve_option_range(field);
    d["unit"] = field.unit;
    d["doc"] = field.doc;
    d["default"] = python_value(value);
    table.append(d);
  });
  return py::tuple(table);
}

py::dict arap_report_dict(const ArapReport& report) {
  py::dict d;
  visit_arap_report(report, [&d](const char* name, const auto& value) { d[name] = report_value(value); });
  return d;
}

} // namespace iarap::python
