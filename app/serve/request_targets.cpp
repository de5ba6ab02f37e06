#include "request_targets.h"

#include "iarap/core/errors.h"
#include "iarap/jobs/deform_job.h"

#include <algorithm>
#include <string>

namespace iarap::serve {
namespace {

Eigen::RowVector3d moved(const Eigen::Matrix4d& M, const Eigen::RowVector3d& p) {
  return (M.topLeftCorner<3, 3>() * p.transpose() + M.topRightCorner<3, 1>()).transpose();
}

void check_affine(const Eigen::Matrix4d& M) {
  if (!M.allFinite()) throw InputError("transform has a non-finite entry");
  const double scale =
      M.topLeftCorner<3, 3>().cwiseAbs().maxCoeff() + M.topRightCorner<3, 1>().cwiseAbs().maxCoeff();
  // The last row of an affine map is exactly 0 0 0 1 up to the rounding of the client's float maths.
  if ((M.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9 * std::max(1.0, scale))
    throw InputError(
        "transform must be affine: its last row (column-major elements 3, 7, 11, 15) must be 0 0 0 1");
}

} // namespace

Eigen::MatrixXd constrained_targets(const Eigen::MatrixXd& anchor, Eigen::Index handle_count,
                                    const SolveRequest& request) {
  Eigen::MatrixXd targets = anchor;
  const Eigen::Index first_handle = anchor.rows() - handle_count;
  if (request.transform && request.handle_targets)
    throw InputError("give either transform or handle_targets, not both");
  if (request.transform) {
    check_affine(*request.transform);
    for (Eigen::Index i = first_handle; i < anchor.rows(); ++i)
      targets.row(i) = moved(*request.transform, targets.row(i));
  } else if (request.handle_targets) {
    const Eigen::MatrixXd& H = *request.handle_targets;
    if (H.rows() != handle_count || H.cols() != 3) {
      throw InputError("handle_targets has " + std::to_string(H.rows() * H.cols()) +
                       " numbers; expected 3 x " + std::to_string(handle_count) +
                       " handle vertices = " + std::to_string(3 * handle_count));
    }
    for (Eigen::Index i = 0; i < H.rows(); ++i) {
      if (!H.row(i).allFinite())
        throw InputError("handle_targets row " + std::to_string(i) + " is not finite");
    }
    targets.bottomRows(handle_count) = H;
  }
  return targets;
}

Eigen::MatrixXd soft_point_targets(const Eigen::MatrixXd& soft_anchor, const SoftSession& soft,
                                   const SolveRequest& request) {
  Eigen::MatrixXd targets = soft_anchor;
  const auto dragged = static_cast<Eigen::Index>(std::count(soft.dragged.begin(), soft.dragged.end(), 1));
  if (request.handle_targets && dragged > 0)
    throw InputError(
        "handle_targets: this session has " + std::to_string(dragged) +
        " weighted handle (soft) vertices, which handle_targets cannot move; drag with transform");
  if (!request.transform) return targets;
  for (Eigen::Index k = 0; k < soft.soft.vertices.size(); ++k)
    if (soft.dragged[static_cast<std::size_t>(k)]) targets.row(k) = moved(*request.transform, targets.row(k));
  return targets;
}

Eigen::MatrixXd request_forces(const MeshData& mesh, const Eigen::VectorXi& constrained,
                               const SoftConstraintSet& soft, const SolveRequest& request) {
  if (!request.gravity && !request.forces) return Eigen::MatrixXd();
  const Eigen::MatrixXd& V = mesh.V;
  Eigen::MatrixXd file_forces;
  if (request.forces) {
    const std::vector<double>& f = *request.forces;
    if (f.size() != static_cast<std::size_t>(3 * V.rows()))
      throw InputError("forces has " + std::to_string(f.size()) + " numbers; expected 3 x " +
                       std::to_string(V.rows()) + " vertices = " + std::to_string(3 * V.rows()) +
                       " (fx fy fz per vertex)");
    file_forces =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(f.data(), V.rows(), 3);
  }
  Eigen::VectorXi faces(soft.faces.size() + soft.hard_faces.size()); // a hard point holds too
  faces << soft.faces, soft.hard_faces;
  try {
    require_held_components(mesh.F, static_cast<int>(V.rows()), constrained, soft.vertices, faces);
  } catch (const InputError& e) { // the request is well formed; the mesh cannot take it (422)
    throw TopologyError(std::string("gravity / forces: ") + e.what());
  }
  StaticForces statics;
  statics.present = true;
  if (request.gravity) statics.gravity = *request.gravity;
  statics.density = request.density;
  return static_forces(V, mesh.F, request.method, statics, file_forces, 1.0);
}

} // namespace iarap::serve
