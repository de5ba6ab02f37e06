// The undo history of a session's constraints: each revision keeps the fixed and handle sets, the rigid
// groups, every
// method's anchors and the soft constraints, so that POST /api/constraints {"revision": R} brings one back.
// A bounded deque (oldest first), since a drag records nothing but a selection records one revision.
#pragma once
#include "iarap/scene/constraint_set.h"

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <deque>
#include <vector>

namespace iarap::serve {

// The soft constraints of a loaded file (soft vertices, soft and hard points on faces): soft.*_targets are
// the file's. dragged (#soft vertices) marks the soft vertices a drag moves with the handle: those of a
// scenario's weighted handles, and in a constraints file those whose target is not their rest position.
// Points on faces are never dragged: they keep their targets.
struct SoftSession {
  SoftConstraintSet soft;
  std::vector<char> dragged;
};

struct Revision {
  int id = 0;
  Eigen::VectorXi fixed, handle;
  std::vector<Eigen::VectorXi> rigid_groups;
  std::array<Eigen::MatrixXd, 3> anchors, soft_anchors; // per method (ArapMethod as an index)
  SoftSession soft;
  int soft_version = 0;
};

class ConstraintHistory {
public:
  static constexpr std::size_t limit = 200;

  // Numbers revision (1, 2, ... over the session's life), keeps it as the newest, drops the oldest past
  // limit; returns its id.
  int record(Revision revision);
  // The revision with this id, moved to the newest place (so that it outlives the revisions undone past
  // it); nullptr when it is no longer kept.
  const Revision* restore(int id);
  // The newest revision's id, 0 before any.
  int newest() const { return revisions_.empty() ? 0 : revisions_.back().id; }
  // Forgets every revision (a new mesh: they index the previous mesh's vertices); ids keep counting.
  void clear() { revisions_.clear(); }

private:
  std::deque<Revision> revisions_; // oldest first, at most limit
  int next_id_ = 1;
};

} // namespace iarap::serve
