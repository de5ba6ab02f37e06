#include "keyword_signature.h"

#include <stdexcept>
#include <utility>

namespace iarap::python {

KeywordSignature::KeywordSignature(std::string function, std::vector<Parameter> parameters,
                                   std::string returns)
    : function_(std::move(function)), returns_(std::move(returns)), parameters_(std::move(parameters)) {}

std::string KeywordSignature::text() const {
  std::string line = function_ + "(self";
  bool star = false;
  for (const Parameter& p : parameters_) {
    if (p.keyword_only && !star) {
      line += ", *";
      star = true;
    }
    line += ", " + p.name + ": " + p.annotation;
    if (p.default_value) line += " = " + py::repr(p.default_value).cast<std::string>();
  }
  return line + ") -> " + returns_;
}

const py::object& BoundArguments::operator[](const std::string& name) const {
  const std::vector<Parameter>& parameters = signature_.parameters();
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (parameters[k].name == name) return values_[k];
  throw std::logic_error(signature_.function() + "() has no parameter '" + name + "'");
}

void BoundArguments::throw_type_error(const std::string& name, const py::object& value) const {
  std::string annotation;
  for (const Parameter& p : signature_.parameters())
    if (p.name == name) annotation = p.annotation;
  throw py::type_error(signature_.function() + "() argument '" + name + "' must be " + annotation + ", got " +
                       py::str(value.get_type().attr("__name__")).cast<std::string>());
}

BoundArguments KeywordSignature::bind(const py::args& args, const py::kwargs& kwargs) const {
  std::size_t positional = 0;
  while (positional < parameters_.size() && !parameters_[positional].keyword_only) ++positional;
  if (args.size() > positional)
    throw py::type_error(function_ + "() takes at most " + std::to_string(positional) +
                         " positional arguments after self (" + std::to_string(args.size()) + " given)");
  std::vector<py::object> values(parameters_.size());
  for (std::size_t k = 0; k < args.size(); ++k) values[k] = py::reinterpret_borrow<py::object>(args[k]);
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    std::size_t k = 0;
    while (k < parameters_.size() && parameters_[k].name != name) ++k;
    if (k == parameters_.size())
      throw py::type_error(function_ + "() got an unexpected keyword argument '" + name + "'");
    if (values[k]) throw py::type_error(function_ + "() got multiple values for argument '" + name + "'");
    values[k] = py::reinterpret_borrow<py::object>(value);
  }
  for (std::size_t k = 0; k < parameters_.size(); ++k) {
    if (values[k]) continue;
    if (!parameters_[k].default_value)
      throw py::type_error(function_ + "() missing required argument '" + parameters_[k].name + "'");
    values[k] = parameters_[k].default_value;
  }
  return BoundArguments(*this, std::move(values));
}

} // namespace iarap::python
