#include "iarap/scene/scenario.h"
#include "../core/math_constants.h"

#include "iarap/core/errors.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace iarap {
namespace {

std::vector<int> select_union(const std::vector<Region>& regions, const Eigen::MatrixXd& V,
                              const BoundingBox& box) {
  std::vector<int> all;
  for (const auto& region : regions) {
    const auto part = select_region(region, V, box);
    all.insert(all.end(), part.begin(), part.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

} // namespace

ConstraintSet resolve_scenario(const Scenario& scenario, const Eigen::MatrixXd& V) {
  const BoundingBox box = bounding_box(V);
  // owner[i]: -1 free, 0 fixed, h + 1 handle h; owner_path names who claimed it first.
  std::vector<int> owner(static_cast<std::size_t>(V.rows()), -1);
  std::vector<int> fixed;
  std::vector<Eigen::Vector3d> targets;
  std::vector<std::string> origins;
  std::vector<int> soft;
  std::vector<double> soft_weights;
  std::vector<Eigen::Vector3d> soft_targets;
  std::vector<std::string> soft_origins;
  const auto claim = [&](int vertex, int who, const std::string& path) {
    int& current = owner[static_cast<std::size_t>(vertex)];
    if (current != -1) {
      const std::string other = current == 0 ? std::string("the fixed set")
                                             : scenario.handles[static_cast<std::size_t>(current - 1)].path;
      throw InputError(path + ": vertex " + std::to_string(vertex) + " is also in " + other +
                       "; a vertex can have only one target");
    }
    current = who;
  };

  if (!scenario.fixed.empty()) {
    for (const int i : select_union(scenario.fixed, V, box)) {
      claim(i, 0, scenario.fixed.front().path);
      fixed.push_back(i);
      targets.emplace_back(V.row(i).transpose());
      origins.push_back(scenario.fixed.front().path);
    }
  }
  for (std::size_t h = 0; h < scenario.handles.size(); ++h) {
    const Handle& handle = scenario.handles[h];
    if (handle.vertices.empty()) throw InputError(handle.path + ": handle has no vertex regions");
    const auto vertices = select_union(handle.vertices, V, box);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const int i : vertices) centroid += V.row(i).transpose();
    centroid /= static_cast<double>(vertices.size());
    Eigen::Vector3d center = centroid;
    if (handle.rotation_center) {
      center = handle.rotation_center_relative
                   ? Eigen::Vector3d(box.min + handle.rotation_center->cwiseProduct(box.max - box.min))
                   : *handle.rotation_center;
    }
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (handle.rotation_degrees != 0) {
      const double axis_length = handle.rotation_axis.norm();
      if (!(axis_length > 0) || !std::isfinite(axis_length)) {
        throw InputError(handle.path + ": rotation axis must be a finite non-zero vector");
      }
      R = Eigen::AngleAxisd(handle.rotation_degrees * kPi / 180.0, handle.rotation_axis / axis_length)
              .toRotationMatrix();
    }
    const Eigen::Vector3d t = handle.translation_relative
                                  ? Eigen::Vector3d(handle.translation * box.diagonal())
                                  : handle.translation;
    for (const int i : vertices) {
      claim(i, static_cast<int>(h) + 1, handle.path);
      const bool hard = handle.weight == 0;
      (hard ? fixed : soft).push_back(i);
      (hard ? targets : soft_targets).emplace_back(R * (V.row(i).transpose() - center) + center + t);
      (hard ? origins : soft_origins).push_back(handle.path);
      if (!hard) soft_weights.push_back(handle.weight);
    }
  }
  if (fixed.empty() && soft.empty())
    throw InputError(scenario.source + ": the scenario constrains no vertex");

  ConstraintSet result;
  result.origins = std::move(origins);
  result.fixed = Eigen::Map<const Eigen::VectorXi>(fixed.data(), static_cast<Eigen::Index>(fixed.size()));
  result.targets.resize(static_cast<Eigen::Index>(targets.size()), 3);
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const Eigen::Vector3d& target = targets[k];
    if (!target.allFinite()) {
      throw InputError(scenario.source + ": target of vertex " + std::to_string(fixed[k]) +
                       " is not finite (non-finite rest position or motion)");
    }
    result.targets.row(static_cast<Eigen::Index>(k)) = target.transpose();
  }
  SoftConstraintSet& s = result.soft;
  const auto ns = static_cast<Eigen::Index>(soft.size());
  s.vertices = Eigen::Map<const Eigen::VectorXi>(soft.data(), ns);
  s.vertex_weights = Eigen::Map<const Eigen::VectorXd>(soft_weights.data(), ns);
  s.vertex_targets.resize(ns, 3);
  for (Eigen::Index k = 0; k < ns; ++k) {
    const Eigen::Vector3d& target = soft_targets[static_cast<size_t>(k)];
    if (!target.allFinite())
      throw InputError(scenario.source + ": target of vertex " +
                       std::to_string(soft[static_cast<size_t>(k)]) +
                       " is not finite (non-finite rest position or motion)");
    s.vertex_targets.row(k) = target.transpose();
  }
  s.origins = std::move(soft_origins);
  s.faces.resize(0);
  s.barycentric.resize(0, 3);
  s.face_weights.resize(0);
  s.face_targets.resize(0, 3);
  return result;
}

} // namespace iarap
