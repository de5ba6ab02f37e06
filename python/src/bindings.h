// The parts of the `iarap` Python module, each defined in its own bind_*.cpp and called from module.cpp.
#pragma once
#include <pybind11/pybind11.h>
// Every file of the module sees the same casters (std::vector, std::optional, ...): pybind11 requires it,
// and a unity build that batched a file without them before one with them bound the wrong ones.
#include <pybind11/stl.h>

namespace iarap::python {

namespace py = pybind11;

// Error, and its subclasses InputError, TopologyError (also ValueError) and SolverError (also RuntimeError).
void bind_errors(py::module_& m);
// read_mesh, write_mesh, check_mesh.
void bind_io(py::module_& m);
// The ARAP class (precompute once, solve often).
void bind_arap(py::module_& m);
// laplacian(V, F, kind) as scipy.sparse.csr_matrix.
void bind_laplacian(py::module_& m);
// intrinsic_delaunay(V, F): intrinsic triangulation, traced segments and B.
void bind_intrinsic(py::module_& m);
// parameterize(V, F, ...): ARAP UV map of a disk and its report.
void bind_param(py::module_& m);
// Simulation (implicit-Euler ARAP dynamics) and vertex_masses.
void bind_dynamics(py::module_& m);
// deform_file(mesh, scenario=..., constraints=...): the job of `iarap deform`.
void bind_deform_job(py::module_& m);
// register(V, F, target_points, ...): non-rigid ICP with ARAP as the regularizer.
void bind_register(py::module_& m);

} // namespace iarap::python
