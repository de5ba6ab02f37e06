#include "iarap/laplacian/mass_matrix.h"
#include "../mesh/face_index_range.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"
#include "intrinsic_for_mesh.h"

#include <optional>
#include <string>

namespace iarap {

Eigen::VectorXd lumped_vertex_areas(const Eigen::MatrixXi& F, const Eigen::MatrixXd& l, int num_vertices,
                                    MassKind kind) {
  Eigen::VectorXd area = Eigen::VectorXd::Zero(num_vertices);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double A = triangle_area_from_lengths(l(f, 0), l(f, 1), l(f, 2));
    double share[3] = {A / 3.0, A / 3.0, A / 3.0};
    if (kind == MassKind::Voronoi) {
      int obtuse = -1;
      for (int k = 0; k < 3; ++k) {
        const double a2 = l(f, k) * l(f, k), b2 = l(f, (k + 1) % 3) * l(f, (k + 1) % 3),
                     c2 = l(f, (k + 2) % 3) * l(f, (k + 2) % 3);
        if (a2 > b2 + c2) obtuse = k;
      }
      if (obtuse >= 0) {
        // Meyer et al.: the circumcentre leaves the triangle, so split by area, half to the obtuse corner.
        for (int k = 0; k < 3; ++k) share[k] = k == obtuse ? A / 2.0 : A / 4.0;
      } else {
        // Circumcentric cell of corner k: (|e_k,k+1|^2 cot(k+2) + |e_k,k+2|^2 cot(k+1)) / 8; the side
        // opposite corner m has length l(f, m).
        double cot[3];
        for (int k = 0; k < 3; ++k)
          cot[k] = cotangent_from_lengths(l(f, k), l(f, (k + 1) % 3), l(f, (k + 2) % 3));
        for (int k = 0; k < 3; ++k) {
          const int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          share[k] = (l(f, k1) * l(f, k1) * cot[k1] + l(f, k2) * l(f, k2) * cot[k2]) / 8.0;
        }
      }
    }
    for (int k = 0; k < 3; ++k) area(F(f, k)) += share[k];
  }
  return area;
}

Eigen::SparseMatrix<double> mass_matrix(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, MassKind kind,
                                        bool intrinsic, const IntrinsicDelaunay* precomputed) {
  const int num_vertices = static_cast<int>(V.rows());
  require_face_indices_in_range(F, num_vertices);
  Eigen::VectorXd area;
  if (intrinsic) {
    std::optional<IntrinsicDelaunay> storage;
    const IntrinsicTriangulation& T = detail::intrinsic_for_mesh(V, F, precomputed, storage).triangulation;
    Eigen::MatrixXd l(T.F.rows(), 3);
    for (Eigen::Index f = 0; f < T.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) l(f, k) = T.length(T.FE(f, k));
    area = lumped_vertex_areas(T.F, l, num_vertices, kind);
  } else {
    Eigen::MatrixXd l(F.rows(), 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) l(f, k) = (V.row(F(f, (k + 1) % 3)) - V.row(F(f, (k + 2) % 3))).norm();
    area = lumped_vertex_areas(F, l, num_vertices, kind);
  }
  Eigen::SparseMatrix<double> M(num_vertices, num_vertices);
  M.reserve(Eigen::VectorXi::Ones(num_vertices));
  for (int i = 0; i < num_vertices; ++i) M.insert(i, i) = area(i);
  return M;
}

const std::vector<std::string>& mass_kind_names() {
  static const std::vector<std::string> names{"voronoi", "barycentric", "intrinsic"};
  return names;
}

MassMatrixChoice parse_mass_kind(const std::string& name) {
  if (name == "voronoi") return {MassKind::Voronoi, false};
  if (name == "barycentric") return {MassKind::Barycentric, false};
  if (name == "intrinsic") return {MassKind::Voronoi, true};
  throw InputError("unknown mass matrix kind '" + name + "'; expected voronoi, barycentric or intrinsic");
}

} // namespace iarap
