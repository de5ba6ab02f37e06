// The Laplace-Beltrami operators of paper Section 6 as scipy.sparse.csr_matrix.
#include "bindings.h"
#include "numpy_arrays.h"

#include "iarap/laplacian/laplacians.h"

namespace iarap::python {
namespace {

py::object laplacian_py(const py::object& V, const py::object& F, const std::string& kind) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  const LaplacianKind which = parse_laplacian_kind(kind);
  Eigen::SparseMatrix<double> L;
  {
    py::gil_scoped_release release;
    L = laplacian(positions, faces, which);
  }
  return to_csr(L);
}

} // namespace

void bind_laplacian(py::module_& m) {
  m.def(
      "laplacian", &laplacian_py, py::arg("V"), py::arg("F"), py::arg("kind") = "cotan",
      R"(A Laplace-Beltrami operator of the mesh (V (#V, 3), F (#F, 3)) as a scipy.sparse.csr_matrix (#V, #V).

Sign convention: -Delta, L[i, j] = -w_ij off the diagonal and zero row sums, so a symmetric operator with
positive weights is positive semi-definite. Weights are dimensionless (cotangents); multiply by the inverse
mass matrix for a pointwise operator.
kind: "cotan" (extrinsic cotan weights), "intrinsic" (cotan Laplacian of the intrinsic Delaunay
triangulation), "iarap" (B^T D_w B of the iARAP global step, Eq. 17), "iarap-plus" (asymmetric
first-segment operator L+), "iarap-sym" (first segment from each end, symmetric), "iarap-refined" (B^T D_w B of
the boundary-robust iARAP, whose obtuse boundary edges are split).
Raises ValueError for bad arrays, an unknown kind or a non-manifold mesh.)");
  py::tuple kinds(all_laplacian_kinds().size());
  for (std::size_t k = 0; k < all_laplacian_kinds().size(); ++k)
    kinds[k] = laplacian_kind_name(all_laplacian_kinds()[k]);
  m.attr("LAPLACIAN_KINDS") = kinds;
}

} // namespace iarap::python
