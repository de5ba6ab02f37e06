// A Python signature assembled at run time, for bindings whose keywords come from a schema (the solve
// options): pybind11 fixes a function's parameters at compile time, one C++ argument per keyword, so such
// a binding takes (*args, **kwargs), binds them here as Python would, and shows this signature as the first
// line of its docstring (written with py::options().disable_function_signatures()).
#pragma once
#include "bindings.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace iarap::python {

struct Parameter {
  std::string name;
  std::string annotation;   // Python type text for the signature line: "float", "npt.ArrayLike | None"
  py::object default_value; // a null handle: required
  bool keyword_only = false;
};

class KeywordSignature;

// The arguments of one call by parameter name, defaults filled in (KeywordSignature::bind).
class BoundArguments {
public:
  BoundArguments(const KeywordSignature& signature, std::vector<py::object> values)
      : signature_(signature), values_(std::move(values)) {}

  // The value of parameter `name` (std::logic_error for a name the signature lacks: a binding's bug).
  const py::object& operator[](const std::string& name) const;

  // The same as a T; TypeError in Python's words when it is not one: "__init__() argument 'dt' must be
  // float, got str".
  template <typename T> T as(const std::string& name) const {
    const py::object& value = (*this)[name];
    try {
      return value.cast<T>();
    } catch (const py::cast_error&) {
      throw_type_error(name, value);
    }
  }

private:
  [[noreturn]] void throw_type_error(const std::string& name, const py::object& value) const;

  const KeywordSignature& signature_;
  std::vector<py::object> values_;
};

class KeywordSignature {
public:
  KeywordSignature(std::string function, std::vector<Parameter> parameters, std::string returns);

  // "solve(self, targets: object, U0: object = None, iterations: int = 50, *, ...) -> numpy.ndarray"
  std::string text() const;

  // The value of every parameter (defaults filled in). Raises TypeError in Python's words for too many
  // positional arguments, an unknown keyword, a value given twice or a missing required one.
  BoundArguments bind(const py::args& args, const py::kwargs& kwargs) const;

  const std::string& function() const { return function_; }
  const std::vector<Parameter>& parameters() const { return parameters_; }

private:
  std::string function_, returns_;
  std::vector<Parameter> parameters_;
};

// m.def(name) of a function taking (*args, **kwargs) bound by `signature` and passed to f as BoundArguments;
// its docstring is the signature line, a blank line and `doc` (pybind11's own signature line is off).
template <typename Function>
void def_with_signature(py::module_& m, KeywordSignature signature, Function f, const std::string& doc) {
  const auto bound = std::make_shared<const KeywordSignature>(std::move(signature));
  py::options options;
  options.disable_function_signatures();
  const std::string text = bound->text() + "\n\n" + doc;
  m.def(
      bound->function().c_str(),
      [bound, f](const py::args& args, const py::kwargs& kwargs) { return f(bound->bind(args, kwargs)); },
      text.c_str());
}

} // namespace iarap::python
