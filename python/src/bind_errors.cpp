// The library's typed exceptions as Python exceptions: bad input is a ValueError, a failed solve a
// RuntimeError, so that callers can catch the built-in classes or the specific ones.
#include "bindings.h"

#include "iarap/core/errors.h"

namespace iarap::python {

void bind_errors(py::module_& m) {
  // pybind11 tries translators newest first, so the base class goes first to be tried last.
  py::register_exception<iarap::Error>(m, "Error", PyExc_RuntimeError);
  py::register_exception<iarap::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<iarap::TopologyError>(m, "TopologyError", PyExc_ValueError);
  py::register_exception<iarap::SolverError>(m, "SolverError", PyExc_RuntimeError);
}

} // namespace iarap::python
