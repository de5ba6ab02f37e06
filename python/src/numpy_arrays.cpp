#include "numpy_arrays.h"

#include "iarap/core/errors.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <sstream>

namespace iarap::python {
namespace {

// "(10, 2)" or "(10,)", as numpy prints shapes.
std::string shape_text(const py::array& a) {
  std::ostringstream out;
  out << "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) out << (d ? ", " : "") << a.shape(d);
  out << (a.ndim() == 1 ? ",)" : ")");
  return out.str();
}

std::string dtype_text(const py::array& a) {
  return py::str(a.dtype()).cast<std::string>();
}

// numpy.asarray(object) without copying when it already is an array; InputError when numpy cannot.
py::array as_array(const py::handle& object, const std::string& name) {
  py::array a = py::array::ensure(object);
  if (!a)
    throw InputError(name + " cannot be converted to a numeric array (got " +
                     py::str(py::type::of(object)).cast<std::string>() + ")");
  return a;
}

bool is_integer_kind(char kind) {
  return kind == 'i' || kind == 'u';
}

// The entries of an integer array, C order, as int64. uint64 entries past the int64 range are reported
// at where(k) (the position of flat entry k) with their true value.
std::vector<std::int64_t> integer_values(const py::array& a, const std::string& name, const char* what,
                                         const std::function<std::string(std::size_t)>& where) {
  const char kind = a.dtype().kind();
  if (a.size() == 0 && kind == 'f') return {}; // np.array([]) is float64: an empty list of indices
  if (!is_integer_kind(kind))
    throw InputError(name + " must hold integer " + what + ", got dtype " + dtype_text(a));
  std::vector<std::int64_t> values(static_cast<std::size_t>(a.size()));
  if (kind == 'u' && a.itemsize() == 8) {
    const auto c = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!c) throw py::error_already_set();
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::uint64_t value = c.data()[k];
      if (value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        throw InputError(where(k) + " is " + std::to_string(value) + ", outside the range of a 32-bit index");
      values[k] = static_cast<std::int64_t>(value);
    }
    return values;
  }
  const auto c = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!c) throw py::error_already_set();
  std::copy(c.data(), c.data() + values.size(), values.begin());
  return values;
}

// Checks one index against 0..vertex_count-1 (or the int range when vertex_count < 0).
void check_index(std::int64_t value, Eigen::Index vertex_count, const std::string& where) {
  if (vertex_count >= 0 && (value < 0 || value >= vertex_count)) {
    throw InputError(where + " is " + std::to_string(value) + ", not a vertex: indices are 0-based and " +
                     "the mesh has " + std::to_string(vertex_count) + " vertices");
  }
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    throw InputError(where + " is " + std::to_string(value) + ", outside the range of a 32-bit index");
}

template <typename Matrix> py::array_t<double> doubles_to_numpy(const Matrix& M) {
  py::array_t<double> a({static_cast<py::ssize_t>(M.rows()), static_cast<py::ssize_t>(M.cols())});
  auto out = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) out(i, j) = M(i, j);
  return a;
}

template <typename Matrix> py::array_t<std::int64_t> ints_to_numpy(const Matrix& M) {
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(M.rows()), static_cast<py::ssize_t>(M.cols())});
  auto out = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    for (Eigen::Index j = 0; j < M.cols(); ++j) out(i, j) = M(i, j);
  return a;
}

template <typename Container> py::array_t<double> vector_to_numpy(const Container& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

template <typename Container> py::array_t<std::int64_t> index_vector_to_numpy(const Container& v) {
  py::array_t<std::int64_t> a(static_cast<py::ssize_t>(v.size()));
  std::int64_t* out = a.mutable_data();
  for (std::size_t k = 0; k < static_cast<std::size_t>(v.size()); ++k) out[k] = v.data()[k];
  return a;
}

} // namespace

Eigen::MatrixXd to_points(const py::handle& object, const std::string& name, bool require_finite,
                          Eigen::Index expected_rows, const std::string& rows_label, bool planar) {
  const py::array a = as_array(object, name);
  const char kind = a.dtype().kind();
  if (kind != 'f' && !is_integer_kind(kind))
    throw InputError(name + " must hold real coordinates, got dtype " + dtype_text(a));
  const std::string columns = planar ? "3 (or 2)" : "3";
  const std::string expected = expected_rows < 0 ? "#rows x " + columns
                                                 : rows_label + " x " + columns + " = " +
                                                       std::to_string(expected_rows) + " x " + columns;
  const bool columns_ok = a.ndim() == 2 && (a.shape(1) == 3 || (planar && a.shape(1) == 2));
  if (!columns_ok || (expected_rows >= 0 && a.shape(0) != expected_rows))
    throw InputError(name + " must be a " + expected + " array, got shape " + shape_text(a));
  auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!c) throw py::error_already_set();
  const auto in = c.unchecked<2>();
  Eigen::MatrixXd M(in.shape(0), in.shape(1));
  for (py::ssize_t i = 0; i < in.shape(0); ++i) {
    for (py::ssize_t j = 0; j < in.shape(1); ++j) {
      const double x = in(i, j);
      if (require_finite && !std::isfinite(x)) {
        std::ostringstream message;
        message << name << " row " << i << " column " << j << " is " << x << "; coordinates must be finite";
        throw InputError(message.str());
      }
      M(i, j) = x;
    }
  }
  return M;
}

Eigen::MatrixXi to_faces(const py::handle& object, const std::string& name, Eigen::Index vertex_count,
                         Eigen::Index columns) {
  const py::array a = as_array(object, name);
  if (a.ndim() != 2 || (columns >= 0 && a.shape(1) != columns)) {
    const std::string expected = columns >= 0 ? "#F x " + std::to_string(columns) : "2-D";
    throw InputError(name + " must be a " + expected + " array of vertex indices, got shape " +
                     shape_text(a));
  }
  const Eigen::Index rows = a.shape(0), cols = a.shape(1);
  const auto where = [&](Eigen::Index f, Eigen::Index k) {
    return name + "[" + std::to_string(f) + ", " + std::to_string(k) + "] (face " + std::to_string(f) + ")";
  };
  const std::vector<std::int64_t> values = integer_values(a, name, "vertex indices", [&](std::size_t flat) {
    return where(static_cast<Eigen::Index>(flat) / cols, static_cast<Eigen::Index>(flat) % cols);
  });
  Eigen::MatrixXi M(rows, cols);
  for (Eigen::Index f = 0; f < rows; ++f) {
    for (Eigen::Index k = 0; k < cols; ++k) {
      const std::int64_t value = values[static_cast<std::size_t>(f * cols + k)];
      check_index(value, vertex_count, where(f, k));
      M(f, k) = static_cast<int>(value);
    }
  }
  return M;
}

Eigen::VectorXi to_indices(const py::handle& object, const std::string& name, Eigen::Index vertex_count) {
  const py::array a = as_array(object, name);
  if (a.ndim() != 1)
    throw InputError(name + " must be a 1-D array of vertex indices, got shape " + shape_text(a));
  const auto where = [&](std::size_t k) { return name + "[" + std::to_string(k) + "]"; };
  const std::vector<std::int64_t> values = integer_values(a, name, "vertex indices", where);
  Eigen::VectorXi v(static_cast<Eigen::Index>(values.size()));
  for (std::size_t k = 0; k < values.size(); ++k) {
    check_index(values[k], vertex_count, where(k));
    v(static_cast<Eigen::Index>(k)) = static_cast<int>(values[k]);
  }
  return v;
}

std::string to_path(const py::handle& path) {
  py::object text = py::module_::import("os").attr("fsdecode")(path);
  return text.cast<std::string>();
}

py::array_t<double> to_numpy(const Eigen::MatrixXd& M) {
  return doubles_to_numpy(M);
}
py::array_t<double> to_numpy(const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& M) {
  return doubles_to_numpy(M);
}
py::array_t<double> to_numpy(const Eigen::VectorXd& v) {
  return vector_to_numpy(v);
}
py::array_t<double> to_numpy(const std::vector<double>& v) {
  return vector_to_numpy(v);
}
py::array_t<std::int64_t> to_numpy(const Eigen::MatrixXi& M) {
  return ints_to_numpy(M);
}
py::array_t<std::int64_t> to_numpy(const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>& M) {
  return ints_to_numpy(M);
}
py::array_t<std::int64_t> to_numpy(const Eigen::VectorXi& v) {
  return index_vector_to_numpy(v);
}
py::array_t<std::int64_t> to_numpy(const std::vector<int>& v) {
  return index_vector_to_numpy(v);
}

py::object to_csr(const Eigen::SparseMatrix<double>& A) {
  Eigen::SparseMatrix<double, Eigen::RowMajor, int> R = A;
  R.makeCompressed();
  const auto nnz = static_cast<py::ssize_t>(R.nonZeros());
  py::array_t<double> data(nnz);
  py::array_t<std::int32_t> indices(nnz);
  py::array_t<std::int32_t> indptr(static_cast<py::ssize_t>(R.rows()) + 1);
  std::copy(R.valuePtr(), R.valuePtr() + nnz, data.mutable_data());
  std::copy(R.innerIndexPtr(), R.innerIndexPtr() + nnz, indices.mutable_data());
  std::copy(R.outerIndexPtr(), R.outerIndexPtr() + R.rows() + 1, indptr.mutable_data());
  py::object csr_matrix = py::module_::import("scipy.sparse").attr("csr_matrix");
  return csr_matrix(py::make_tuple(data, indices, indptr),
                    py::arg("shape") = py::make_tuple(R.rows(), R.cols()));
}

Eigen::Vector3d to_vector3(const py::object& value, const std::string& name) {
  const py::object flat = py::module_::import("numpy").attr("ravel")(value);
  const auto count = py::len(flat);
  if (count != 3) throw InputError(name + ": want 3 numbers (x, y, z), got " + std::to_string(count));
  const Eigen::MatrixXd g = to_points(flat.attr("reshape")(1, 3), name, true, 1, "1");
  return g.row(0).transpose();
}

} // namespace iarap::python
