// The library's typed exceptions as Python exceptions. All derive from iarap.Error; bad input is also a
// ValueError and a failed solve a RuntimeError, so callers can catch the built-in classes or ours.
#include "bindings.h"

#include "iarap/core/errors.h"

namespace iarap::python {

void bind_errors(py::module_& m) {
  // pybind11 tries translators newest first, so the base class goes first to be tried last.
  const py::handle error = py::register_exception<iarap::Error>(m, "Error", PyExc_Exception);
  py::register_exception<iarap::InputError>(m, "InputError",
                                            py::make_tuple(error, py::handle(PyExc_ValueError)));
  py::register_exception<iarap::TopologyError>(m, "TopologyError",
                                               py::make_tuple(error, py::handle(PyExc_ValueError)));
  py::register_exception<iarap::SolverError>(m, "SolverError",
                                             py::make_tuple(error, py::handle(PyExc_RuntimeError)));
}

} // namespace iarap::python
