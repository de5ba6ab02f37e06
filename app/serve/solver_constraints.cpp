#include "solver_constraints.h"

#include "iarap/core/errors.h"

#include <cmath>
#include <string>

namespace iarap::serve {

bool same_indices(const Eigen::VectorXi& a, const Eigen::VectorXi& b) {
  return a.size() == b.size() && (a.size() == 0 || a == b);
}

void set_soft_targets(SoftConstraintSet& set, const Eigen::MatrixXd& T) {
  const Eigen::Index sv = set.vertices.size(), sb = set.faces.size();
  set.vertex_targets = T.topRows(sv);
  set.face_targets = T.middleRows(sv, sb);
  set.hard_targets = T.bottomRows(set.hard_faces.size());
}

SolverConstraints solver_constraints(const Eigen::VectorXi& fixed, const Eigen::VectorXi& handle,
                                     const Eigen::MatrixXd& targets, const SoftConstraintSet& file_soft,
                                     const std::optional<Eigen::VectorXd>& handle_weights) {
  SolverConstraints out;
  out.soft = file_soft;
  if (!handle_weights) {
    out.hard.resize(fixed.size() + handle.size());
    out.hard << fixed, handle;
    out.hard_targets = targets;
    return out;
  }
  const Eigen::VectorXd& w = *handle_weights;
  if (handle.size() == 0)
    throw InputError("handle_weights: there is no handle vertex to make soft; select a handle first");
  if (w.size() != handle.size())
    throw InputError("handle_weights has " + std::to_string(w.size()) +
                     " weights; expected one per handle vertex (" + std::to_string(handle.size()) + ")");
  for (Eigen::Index k = 0; k < w.size(); ++k)
    if (!std::isfinite(w[k]) || !(w[k] > 0))
      throw InputError("handle_weights[" + std::to_string(k) + "] = " + std::to_string(w[k]) +
                       " must be finite and > 0 (omit handle_weights for a hard handle)");
  out.soft_handle = true;
  out.hard = fixed;
  out.hard_targets = targets.topRows(fixed.size());
  const Eigen::Index sv = file_soft.vertices.size(), nh = handle.size();
  out.soft.vertices.resize(sv + nh);
  out.soft.vertices << file_soft.vertices, handle;
  out.soft.vertex_weights.resize(sv + nh);
  out.soft.vertex_weights << file_soft.vertex_weights, w;
  out.soft.vertex_targets.resize(sv + nh, 3);
  if (sv > 0) out.soft.vertex_targets.topRows(sv) = file_soft.vertex_targets;
  out.soft.vertex_targets.bottomRows(nh) = targets.bottomRows(nh);
  // origins: vertices first, then the face points (constraint_set.h); the handle's go after the file's.
  const auto vertex_origins = std::min<std::size_t>(file_soft.origins.size(), static_cast<std::size_t>(sv));
  std::vector<std::string> origins(file_soft.origins.begin(),
                                   file_soft.origins.begin() + static_cast<long>(vertex_origins));
  for (Eigen::Index k = 0; k < nh; ++k) origins.push_back("soft handle vertex " + std::to_string(handle[k]));
  if (file_soft.origins.size() > vertex_origins)
    origins.insert(origins.end(), file_soft.origins.begin() + static_cast<long>(vertex_origins),
                   file_soft.origins.end());
  out.soft.origins = std::move(origins);
  return out;
}

} // namespace iarap::serve
