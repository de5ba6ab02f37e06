#include "iarap/scene/remap_constraints.h"

#include "iarap/core/errors.h"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace iarap {

ConstraintSet remap_constraints(const ConstraintSet& constraints, const Eigen::VectorXi& old_to_new) {
  if (constraints.soft.size() > 0)
    throw InputError(
        "soft constraints (" + constraints.soft.origins.front() +
        ") cannot be carried over a mesh repair yet; repair the mesh first (`iarap repair MESH --out "
        "REPAIRED --map MAP.txt`: MAP.txt says where each vertex went) and give constraints on the "
        "repaired mesh");
  ConstraintSet result;
  result.warnings = constraints.warnings;
  std::vector<int> fixed;
  std::vector<Eigen::Index> source_row;
  std::unordered_map<int, Eigen::Index> first_row; // new index -> row of constraints that claimed it
  for (Eigen::Index k = 0; k < constraints.fixed.size(); ++k) {
    const int old_index = constraints.fixed(k);
    if (old_index < 0 || old_index >= old_to_new.size()) {
      throw InputError("constrained vertex " + std::to_string(old_index) + " is out of range; the mesh had " +
                       std::to_string(old_to_new.size()) + " vertices");
    }
    const int new_index = old_to_new(old_index);
    if (new_index < 0) {
      throw InputError("constrained vertex " + std::to_string(old_index) +
                       " was removed by mesh repair; constrain a vertex that stays");
    }
    const auto found = first_row.find(new_index);
    if (found == first_row.end()) {
      first_row.emplace(new_index, k);
      fixed.push_back(new_index);
      source_row.push_back(k);
    } else if (constraints.targets.row(found->second) != constraints.targets.row(k)) {
      throw InputError("constrained vertices " + std::to_string(constraints.fixed(found->second)) + " and " +
                       std::to_string(old_index) + " were merged by mesh repair into vertex " +
                       std::to_string(new_index) + " but have different targets");
    }
  }
  result.fixed = Eigen::Map<const Eigen::VectorXi>(fixed.data(), static_cast<Eigen::Index>(fixed.size()));
  result.targets.resize(result.fixed.size(), 3);
  for (std::size_t k = 0; k < source_row.size(); ++k) {
    result.targets.row(static_cast<Eigen::Index>(k)) = constraints.targets.row(source_row[k]);
    if (static_cast<Eigen::Index>(constraints.origins.size()) == constraints.fixed.size())
      result.origins.push_back(constraints.origins[static_cast<std::size_t>(source_row[k])]);
  }
  return result;
}

namespace {

std::string origin_of(const SoftConstraintSet& soft, Eigen::Index k, const std::string& what) {
  return static_cast<Eigen::Index>(soft.origins.size()) == soft.size() ? soft.origins[static_cast<size_t>(k)]
                                                                       : what;
}

// Soft vertices: W / k on each of the k copies; welded ones merged (summed weight, weighted mean target).
void remap_soft_vertices(const SoftConstraintSet& soft, const std::vector<std::vector<int>>& copies,
                         const MeshRenumbering& r, SoftConstraintSet& out) {
  std::map<int, std::pair<double, Eigen::RowVector3d>> pull; // new vertex -> (W, sum W t)
  std::map<int, std::string> origin;
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) {
    const int v = soft.vertices(k);
    if (v < 0 || v >= r.old_to_new.size() || r.old_to_new(v) < 0)
      throw InputError(origin_of(soft, k, "soft vertex " + std::to_string(v)) + ": soft vertex " +
                       std::to_string(v) + " was removed by mesh repair (it is used by no face)");
    const std::vector<int>& mine = copies[static_cast<size_t>(r.new_to_old(r.old_to_new(v)))];
    const double W = soft.vertex_weights(k) / static_cast<double>(mine.size());
    for (const int n : mine) {
      auto& [weight, moment] = pull.try_emplace(n, 0.0, Eigen::RowVector3d::Zero()).first->second;
      weight += W;
      moment += W * soft.vertex_targets.row(k);
      origin.try_emplace(n, origin_of(soft, k, "soft vertex " + std::to_string(v)));
    }
  }
  out.vertices.resize(static_cast<Eigen::Index>(pull.size()));
  out.vertex_weights.resize(out.vertices.size());
  out.vertex_targets.resize(out.vertices.size(), 3);
  Eigen::Index row = 0;
  for (const auto& [n, p] : pull) {
    out.vertices(row) = n;
    out.vertex_weights(row) = p.first;
    out.vertex_targets.row(row) = p.second / p.first;
    out.origins.push_back(origin[n]);
    ++row;
  }
}

// The face of the renumbered mesh that stands for each old face: keyed by the sorted old vertices its
// corners stand for.
class FaceFinder {
public:
  explicit FaceFinder(const MeshRenumbering& r) : r_(r) {
    for (Eigen::Index g = 0; g < r.new_F.rows(); ++g) {
      std::array<int, 3> key{r.new_to_old(r.new_F(g, 0)), r.new_to_old(r.new_F(g, 1)),
                             r.new_to_old(r.new_F(g, 2))};
      std::sort(key.begin(), key.end());
      face_.try_emplace(key, static_cast<int>(g));
    }
  }
  // The new face of old face f and the barycentric coordinates B over its corners, or -1 when the
  // repair removed it.
  int find(int f, const Eigen::RowVector3d& B, Eigen::RowVector3d& B_new) const {
    if (f < 0 || f >= r_.old_F.rows()) return -1;
    std::array<int, 3> old_corner{};
    for (int j = 0; j < 3; ++j) {
      const int v = r_.old_F(f, j), n = r_.old_to_new(v);
      if (n < 0) return -1;
      old_corner[static_cast<size_t>(j)] = r_.new_to_old(n);
    }
    std::array<int, 3> key = old_corner;
    std::sort(key.begin(), key.end());
    const auto found = face_.find(key);
    if (found == face_.end() || key[0] == key[1] || key[1] == key[2]) return -1;
    for (int j = 0; j < 3; ++j) {
      const int stands_for = r_.new_to_old(r_.new_F(found->second, j));
      for (int i = 0; i < 3; ++i)
        if (old_corner[static_cast<size_t>(i)] == stands_for) B_new(j) = B(i);
    }
    return found->second;
  }

private:
  const MeshRenumbering& r_;
  std::map<std::array<int, 3>, int> face_;
};

// Points on faces (soft or hard) onto the faces that stand for theirs; rows k of faces/B/targets.
void remap_face_points(const FaceFinder& finder, const Eigen::VectorXi& faces, const Eigen::MatrixXd& B,
                       const SoftConstraintSet& soft, Eigen::Index first_origin, Eigen::VectorXi& faces_out,
                       Eigen::MatrixXd& B_out) {
  faces_out.resize(faces.size());
  B_out.resize(faces.size(), 3);
  for (Eigen::Index k = 0; k < faces.size(); ++k) {
    Eigen::RowVector3d B_new;
    const int f = faces(k);
    const int g = finder.find(f, B.row(k), B_new);
    if (g < 0)
      throw InputError(origin_of(soft, first_origin + k, "point on face " + std::to_string(f)) + ": face " +
                       std::to_string(f) +
                       " was removed by mesh repair (degenerate, collapsed by a weld, or out of range)");
    faces_out(k) = g;
    B_out.row(k) = B_new;
  }
}

// Every copy of each vertex a split made, by the old vertex they stand for, in increasing new index (the
// first copy, old_to_new's, first).
std::vector<std::vector<int>> copies_by_old(const Eigen::VectorXi& new_to_old) {
  std::vector<std::vector<int>> copies(new_to_old.size() > 0 ? static_cast<size_t>(new_to_old.maxCoeff()) + 1
                                                             : 0);
  for (Eigen::Index n = 0; n < new_to_old.size(); ++n)
    copies[static_cast<size_t>(new_to_old(n))].push_back(static_cast<int>(n));
  return copies;
}

} // namespace

void constrain_split_copies(ConstraintSet& constraints, const Eigen::VectorXi& new_to_old) {
  const Eigen::Index n = new_to_old.size(), count = constraints.fixed.size();
  const std::vector<std::vector<int>> copies = copies_by_old(new_to_old);
  std::vector<Eigen::Index> row_of(static_cast<size_t>(n), -1);
  for (Eigen::Index k = 0; k < count; ++k) row_of[static_cast<size_t>(constraints.fixed(k))] = k;
  std::vector<std::pair<int, Eigen::Index>> added; // (copy, row of its constrained first copy)
  for (Eigen::Index v = 0; v < n; ++v) {
    const int first = copies[static_cast<size_t>(new_to_old(v))].front();
    if (first != v && row_of[static_cast<size_t>(v)] < 0 && row_of[static_cast<size_t>(first)] >= 0)
      added.emplace_back(static_cast<int>(v), row_of[static_cast<size_t>(first)]);
  }
  if (added.empty()) return;
  const auto extra = static_cast<Eigen::Index>(added.size());
  constraints.fixed.conservativeResize(count + extra);
  constraints.targets.conservativeResize(count + extra, 3);
  const bool named = static_cast<Eigen::Index>(constraints.origins.size()) == count;
  for (Eigen::Index i = 0; i < extra; ++i) {
    const auto& [copy, row] = added[static_cast<size_t>(i)];
    constraints.fixed(count + i) = copy;
    constraints.targets.row(count + i) = constraints.targets.row(row);
    if (named) constraints.origins.push_back(constraints.origins[static_cast<size_t>(row)]);
  }
}

ConstraintSet remap_constraints(const ConstraintSet& constraints, const MeshRenumbering& renumbering) {
  ConstraintSet hard = constraints;
  hard.soft = SoftConstraintSet{};
  ConstraintSet result = remap_constraints(hard, renumbering.old_to_new);
  constrain_split_copies(result, renumbering.new_to_old);
  const std::vector<std::vector<int>> copies = copies_by_old(renumbering.new_to_old);
  const SoftConstraintSet& soft = constraints.soft;
  if (soft.size() == 0) return result;
  SoftConstraintSet& out = result.soft;
  remap_soft_vertices(soft, copies, renumbering, out);
  const FaceFinder finder(renumbering);
  remap_face_points(finder, soft.faces, soft.barycentric, soft, soft.vertices.size(), out.faces,
                    out.barycentric);
  out.face_weights = soft.face_weights;
  out.face_targets = soft.face_targets;
  remap_face_points(finder, soft.hard_faces, soft.hard_barycentric, soft,
                    soft.vertices.size() + soft.faces.size(), out.hard_faces, out.hard_barycentric);
  out.hard_targets = soft.hard_targets;
  const auto named = static_cast<Eigen::Index>(soft.origins.size()) == soft.size();
  for (Eigen::Index k = soft.vertices.size(); named && k < soft.size(); ++k)
    out.origins.push_back(soft.origins[static_cast<size_t>(k)]);
  if (!named) out.origins.clear();
  return result;
}

} // namespace iarap
