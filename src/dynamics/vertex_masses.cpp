#include "iarap/core/errors.h"
#include "iarap/dynamics/simulation.h"
#include "iarap/laplacian/mass_matrix.h"

#include <cmath>
#include <string>

namespace iarap {

Eigen::VectorXd arap_vertex_masses(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, ArapMethod method,
                                   double density) {
  if (!(std::isfinite(density) && density > 0))
    throw InputError("masses: density must be finite and > 0, got " + std::to_string(density));
  Eigen::MatrixXd V3 = Eigen::MatrixXd::Zero(V.rows(), 3);
  V3.leftCols(std::min<Eigen::Index>(V.cols(), 3)) = V.leftCols(std::min<Eigen::Index>(V.cols(), 3));
  // iARAP's L is the intrinsic cotan Laplacian (twice): its partner is the intrinsic Voronoi mass.
  const Eigen::SparseMatrix<double> M = mass_matrix(V3, F, MassKind::Voronoi, method == ArapMethod::Iarap);
  return density * Eigen::VectorXd(M.diagonal());
}

Eigen::MatrixXd gravity_forces(const Eigen::VectorXd& masses, const Eigen::Vector3d& gravity) {
  if (!gravity.allFinite()) throw InputError("gravity must be finite");
  return masses * gravity.transpose();
}

} // namespace iarap
