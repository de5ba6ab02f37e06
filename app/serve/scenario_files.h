// The viewer's session as files `iarap deform` replays, and such files read back into the session.
//
// Saving: when every anchor is a rest position and the handle's map is rigid (the gizmo translates and
// rotates), the session is exactly a scenario (README "Scenario files"): the fixed indices at rest and one
// handle moved by `rotate` about the origin and `translate`. Otherwise (anchors re-taken on a deformed
// shape, or explicit handle targets) it is written as a constraints file, one "index x y z" per vertex,
// which holds any targets exactly. Soft constraints (weights) and points on faces are written as the
// constraints file's soft lines ("index x y z w", "b face b0 b1 b2 x y z [w]"), so a session with any is
// always a constraints file.
// Loading: a scenario (JSON, told by its first non-blank character '{') is resolved on the rest mesh, its
// fixed vertices stay fixed, its hard handles become the handle and its weighted handles soft vertices the
// drag moves; in a constraints file a vertex whose target is its rest position is fixed and every other one
// is a handle vertex, likewise a soft vertex stays or is dragged, and points on faces keep their targets.
#pragma once
#include "session.h"

#include <Eigen/Core>
#include <string>

namespace iarap::serve {

struct SavedSession {
  std::string text;
  bool is_scenario = false; // false: a constraints file
};

// targets of Session::constraint_targets; transform: the request's 4 x 4 affine map, if it had one.
SavedSession save_session(const ConstraintTargets& targets, const std::optional<Eigen::Matrix4d>& transform,
                          const std::string& description);

struct LoadedSession {
  Eigen::VectorXi fixed, handle;
  Eigen::MatrixXd targets; // #fixed + #handle x 3, fixed rows first
  SoftSession soft;
  std::vector<std::string> warnings;
};

// Parses text (a scenario or constraints file named source) for the rest mesh (V #V x 3, F #F x 3). Throws
// InputError / HttpError 400 naming source and the line or JSON path at fault.
LoadedSession load_session(const std::string& text, const std::string& source, const Eigen::MatrixXd& V,
                           const Eigen::MatrixXi& F);

} // namespace iarap::serve
