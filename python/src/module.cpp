// The extension iarap._core of the `iarap` Python package (python/iarap/__init__.py re-exports it):
// numpy in, numpy and scipy.sparse out, over the C++ library.
#include "bindings.h"

#include "iarap/core/threads.h"
#include "iarap/core/version.h"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  m.doc() = R"(As-rigid-as-possible surface deformation with the iARAP discretization.

Positions are float64 arrays of shape (#V, 3) in the units of the mesh; faces are int64 arrays of shape
(#F, 3) of 0-based vertex indices. Inputs of other real dtypes (float32, int64, ...) and memory orders
(Fortran) are converted. Every error raised on bad input derives from iarap.Error: wrong shapes, NaN or
Inf coordinates, out-of-range indices and unknown names raise iarap.InputError (also a ValueError) naming
the argument and the element. Returned arrays are C-ordered copies that own their memory.

    V, F = iarap.read_mesh("bunny.off")
    solver = iarap.ARAP(V, F, fixed=[0, 1, 2], method="iarap")
    U = solver.solve(V[[0, 1, 2]] + [0.0, 0.01, 0.0])
)";
  m.attr("__version__") = iarap::version();
  iarap::python::bind_errors(m);
  iarap::python::bind_io(m);
  iarap::python::bind_arap(m);
  iarap::python::bind_laplacian(m);
  iarap::python::bind_intrinsic(m);
  iarap::python::bind_param(m);
  iarap::python::bind_dynamics(m);
  iarap::python::bind_deform_job(m);
  iarap::python::bind_register(m);
  m.def("set_thread_count", &iarap::set_thread_count, py::arg("n"),
        "Threads for the library's parallel loops (OpenMP); n <= 0 means all hardware threads.");
  m.def("thread_count", &iarap::thread_count, "Threads the library's parallel loops use.");
}
