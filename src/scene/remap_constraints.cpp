#include "iarap/scene/remap_constraints.h"

#include "iarap/core/errors.h"

#include <unordered_map>

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

} // namespace iarap
