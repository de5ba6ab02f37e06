// Conversion between numpy / scipy objects and the Eigen types of the library. Inputs of any memory
// order and of any real dtype are converted (copied); wrong shapes, dtypes, non-finite values and
// out-of-range indices throw iarap::InputError (Python: iarap.InputError, a ValueError) naming the argument,
// the row and the value.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
// The STL casters in every file of the module (bindings.h says why).
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

namespace iarap::python {

namespace py = pybind11;

// An array-like of real numbers (float, int or uint dtype; any order) as a rows x 3 double matrix (rows x 2
// too when planar: points in the plane). expected_rows < 0 accepts any row count; otherwise rows_label says
// what the count is ("#fixed"). Throws InputError for another dtype or shape, or, when require_finite, a NaN
// or Inf entry.
Eigen::MatrixXd to_points(const py::handle& object, const std::string& name, bool require_finite = true,
                          Eigen::Index expected_rows = -1, const std::string& rows_label = "",
                          bool planar = false);

// An integer array-like with 2 dimensions as an int matrix; columns < 0 accepts any column count. Entries
// must lie in 0..vertex_count-1 when vertex_count >= 0, and always in the range of int.
// Throws InputError for a float or other non-integer dtype, another shape, an entry out of range.
Eigen::MatrixXi to_faces(const py::handle& object, const std::string& name, Eigen::Index vertex_count,
                         Eigen::Index columns = 3);

// A 1-D integer array-like of vertex indices in 0..vertex_count-1.
Eigen::VectorXi to_indices(const py::handle& object, const std::string& name, Eigen::Index vertex_count);

// os.fspath(path) as a string; raises TypeError for objects that are not paths.
std::string to_path(const py::handle& path);

// C-ordered numpy arrays that own a copy of the data (no view into C++ objects that may die first).
// Three finite numbers (any array-like of 3) as a vector; InputError naming `name` otherwise.
Eigen::Vector3d to_vector3(const py::object& value, const std::string& name);

py::array_t<double> to_numpy(const Eigen::MatrixXd& M);
py::array_t<double> to_numpy(const Eigen::VectorXd& v);
py::array_t<double> to_numpy(const std::vector<double>& v);
py::array_t<double> to_numpy(const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& M);
py::array_t<std::int64_t> to_numpy(const Eigen::MatrixXi& M);
py::array_t<std::int64_t> to_numpy(const Eigen::VectorXi& v);
py::array_t<std::int64_t> to_numpy(const std::vector<int>& v);
py::array_t<std::int64_t> to_numpy(const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>& M);

// scipy.sparse.csr_matrix holding a copy of A (float64 data, int32 indices).
py::object to_csr(const Eigen::SparseMatrix<double>& A);

} // namespace iarap::python
