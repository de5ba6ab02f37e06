#include "constraint_history.h"

#include <algorithm>

namespace iarap::serve {

int ConstraintHistory::record(Revision revision) {
  revision.id = next_id_++;
  revisions_.push_back(std::move(revision));
  if (revisions_.size() > limit) revisions_.pop_front();
  return revisions_.back().id;
}

const Revision* ConstraintHistory::restore(int id) {
  const auto it =
      std::find_if(revisions_.begin(), revisions_.end(), [id](const Revision& r) { return r.id == id; });
  if (it == revisions_.end()) return nullptr;
  Revision restored = std::move(*it);
  revisions_.erase(it);
  revisions_.push_back(std::move(restored));
  return &revisions_.back();
}

} // namespace iarap::serve
