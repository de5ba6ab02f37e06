// The Laplace-Beltrami operators of paper Section 6 and the lumped mass matrices, as scipy.sparse.csr_matrix.
#include "bindings.h"
#include "numpy_arrays.h"

#include "iarap/laplacian/laplacians.h"
#include "iarap/laplacian/mass_matrix.h"

#include <optional>

namespace iarap::python {
namespace {

// The mass matrix a Laplacian kind pairs with when laplacian(..., return_mass=True) names none: the
// input mesh's cells for the extrinsic cotan operator, the intrinsic Delaunay cells for the others.
std::string default_mass_for(LaplacianKind kind) {
  return kind == LaplacianKind::Cotan ? "voronoi" : "intrinsic";
}

py::object laplacian_py(const py::object& V, const py::object& F, const std::string& kind, bool return_mass,
                        const std::optional<std::string>& mass) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  const LaplacianKind which = parse_laplacian_kind(kind);
  const MassMatrixChoice mass_choice = parse_mass_kind(mass.value_or(default_mass_for(which)));
  Eigen::SparseMatrix<double> L, M;
  {
    py::gil_scoped_release release;
    // One intrinsic Delaunay triangulation serves both operators when both need it.
    const bool shared = return_mass && mass_choice.intrinsic && which != LaplacianKind::Cotan &&
                        which != LaplacianKind::IarapRefined;
    std::optional<IntrinsicDelaunay> idt;
    if (shared) idt = intrinsic_delaunay(positions, faces);
    L = laplacian(positions, faces, which, idt ? &*idt : nullptr);
    if (return_mass)
      M = mass_matrix(positions, faces, mass_choice.kind, mass_choice.intrinsic, idt ? &*idt : nullptr);
  }
  if (!return_mass) return to_csr(L);
  return py::make_tuple(to_csr(L), to_csr(M));
}

py::object mass_matrix_py(const py::object& V, const py::object& F, const std::string& kind) {
  const Eigen::MatrixXd positions = to_points(V, "V");
  const Eigen::MatrixXi faces = to_faces(F, "F", positions.rows());
  const MassMatrixChoice choice = parse_mass_kind(kind);
  Eigen::SparseMatrix<double> M;
  {
    py::gil_scoped_release release;
    M = mass_matrix(positions, faces, choice.kind, choice.intrinsic);
  }
  return to_csr(M);
}

} // namespace

void bind_laplacian(py::module_& m) {
  m.def(
      "laplacian", &laplacian_py, py::arg("V"), py::arg("F"), py::arg("kind") = "cotan", py::kw_only(),
      py::arg("return_mass") = false, py::arg("mass") = py::none(),
      R"(A Laplace-Beltrami operator of the mesh (V (#V, 3), F (#F, 3)) as a scipy.sparse.csr_matrix (#V, #V).

Sign convention: -Delta, L[i, j] = -w_ij off the diagonal and zero row sums, so a symmetric operator with
positive weights is positive semi-definite. Weights are dimensionless (cotangents); multiply by the inverse
mass matrix for a pointwise operator.
kind: "cotan" (extrinsic cotan weights), "intrinsic" (cotan Laplacian of the intrinsic Delaunay
triangulation), "iarap" (B^T D_w B of the iARAP global step, Eq. 17), "iarap-plus" (asymmetric
first-segment operator L+), "iarap-sym" (first segment from each end, symmetric), "iarap-refined" (B^T D_w B of
the boundary-robust iARAP, whose obtuse boundary edges are split).
return_mass: return (L, M), M the diagonal mass matrix (#V, #V) of kind `mass` (see mass_matrix); None
takes "voronoi" for kind "cotan" and "intrinsic" for the others. Then L u = lambda M u is the discrete
eigenproblem of -Delta, and M^-1 L the pointwise operator.
Raises InputError (a ValueError) for bad arrays or an unknown kind, TopologyError (a ValueError) for a
non-manifold mesh.)");
  m.def("mass_matrix", &mass_matrix_py, py::arg("V"), py::arg("F"), py::arg("kind") = "voronoi",
        R"(The lumped (diagonal) mass matrix of (V (#V, 3), F (#F, 3)) as a scipy.sparse.csr_matrix (#V, #V):
M[i, i] is the area of vertex i's cell, in squared mesh units; the cells partition the surface, so the
diagonal sums to its area.

kind: "voronoi" (mixed Voronoi cells of the mesh, Meyer et al. 2003: circumcentric, with the area split
1/2, 1/4, 1/4 in obtuse triangles), "barycentric" (a third of each incident triangle), "intrinsic" (mixed
Voronoi cells of the intrinsic Delaunay triangulation, the cells of iARAP's energy).
Raises InputError (a ValueError) for bad arrays or an unknown kind, TopologyError (a ValueError) for a
non-manifold mesh ("intrinsic").)");
  py::tuple kinds(all_laplacian_kinds().size());
  for (std::size_t k = 0; k < all_laplacian_kinds().size(); ++k)
    kinds[k] = laplacian_kind_name(all_laplacian_kinds()[k]);
  m.attr("LAPLACIAN_KINDS") = kinds;
  py::tuple mass_kinds(mass_kind_names().size());
  for (std::size_t k = 0; k < mass_kind_names().size(); ++k) mass_kinds[k] = mass_kind_names()[k];
  m.attr("MASS_KINDS") = mass_kinds;
}

} // namespace iarap::python
