#include "scenario_files.h"

#include "json_input.h"

#include "iarap/core/errors.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/scene/read_scenario.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

namespace iarap::serve {
namespace {

using nlohmann::json;

std::vector<int> to_list(const Eigen::VectorXi& v) {
  return std::vector<int>(v.data(), v.data() + v.size());
}

// The 3 x 3 part of an affine map is a rotation when R^T R = I and det R = 1 up to the rounding of the
// browser's double maths (quaternion to matrix: a few ulps).
bool is_rigid(const Eigen::Matrix4d& M) {
  const Eigen::Matrix3d R = M.topLeftCorner<3, 3>();
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <= 1e-9 &&
         R.determinant() > 0;
}

std::string scenario_text(const ConstraintTargets& targets, const Eigen::Matrix4d& M,
                          const std::string& description) {
  json scenario = {{"description", description}};
  if (targets.fixed.size() > 0) scenario["fixed"] = {{"indices", to_list(targets.fixed)}};
  if (targets.handle.size() > 0) {
    // target = R v + t: the scenario's rotation about the centre (0, 0, 0), then its translation.
    const Eigen::AngleAxisd rotation(Eigen::Matrix3d(M.topLeftCorner<3, 3>()));
    const Eigen::Vector3d t = M.topRightCorner<3, 1>();
    json handle = {{"name", "handle"},
                   {"vertices", {{"indices", to_list(targets.handle)}}},
                   {"translate", {t.x(), t.y(), t.z()}}};
    if (rotation.angle() != 0) {
      const Eigen::Vector3d& axis = rotation.axis();
      handle["rotate"] = {{"axis", {axis.x(), axis.y(), axis.z()}},
                          {"degrees", rotation.angle() * 180.0 / M_PI},
                          {"center", {0.0, 0.0, 0.0}}};
    }
    scenario["handles"] = json::array({handle});
  }
  return scenario.dump(2) + "\n";
}

std::string constraints_text(const ConstraintTargets& targets, const std::string& description) {
  std::ostringstream out;
  out << "# " << description << "\n# index x y z (" << targets.fixed.size() << " fixed, then "
      << targets.handle.size() << " handle vertices)\n";
  char line[256];
  for (Eigen::Index i = 0; i < targets.targets.rows(); ++i) {
    const int vertex = i < targets.fixed.size() ? targets.fixed[i] : targets.handle[i - targets.fixed.size()];
    // %.17g: every double written so that it reads back bit for bit.
    std::snprintf(line, sizeof line, "%d %.17g %.17g %.17g\n", vertex, targets.targets(i, 0),
                  targets.targets(i, 1), targets.targets(i, 2));
    out << line;
  }
  const SoftConstraintSet& soft = targets.soft;
  if (soft.size() > 0)
    out << "# soft: index x y z weight, then points on faces: b face b0 b1 b2 x y z [weight]\n";
  for (Eigen::Index k = 0; k < soft.vertices.size(); ++k) {
    const auto t = soft.vertex_targets.row(k);
    std::snprintf(line, sizeof line, "%d %.17g %.17g %.17g %.17g\n", soft.vertices[k], t(0), t(1), t(2),
                  soft.vertex_weights[k]);
    out << line;
  }
  const auto face_point = [&](int face, const auto& b, const auto& t) {
    std::snprintf(line, sizeof line, "b %d %.17g %.17g %.17g %.17g %.17g %.17g", face, b(0), b(1), b(2), t(0),
                  t(1), t(2));
    out << line;
  };
  for (Eigen::Index k = 0; k < soft.faces.size(); ++k) {
    face_point(soft.faces[k], soft.barycentric.row(k), soft.face_targets.row(k));
    std::snprintf(line, sizeof line, " %.17g\n", soft.face_weights[k]);
    out << line;
  }
  for (Eigen::Index k = 0; k < soft.hard_faces.size(); ++k) {
    face_point(soft.hard_faces[k], soft.hard_barycentric.row(k), soft.hard_targets.row(k));
    out << "\n";
  }
  return out.str();
}

} // namespace

SavedSession save_session(const ConstraintTargets& targets, const std::optional<Eigen::Matrix4d>& transform,
                          const std::string& description) {
  const Eigen::Matrix4d M = transform.value_or(Eigen::Matrix4d::Identity());
  if (targets.soft.size() == 0 && targets.anchored_at_rest && is_rigid(M))
    return {scenario_text(targets, M, description), true};
  return {constraints_text(targets, description), false};
}

LoadedSession load_session(const std::string& text, const std::string& source, const Eigen::MatrixXd& V,
                           const Eigen::MatrixXi& F) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  LoadedSession out;
  if (first != std::string::npos && text[first] == '{') {
    check_json_limits(text); // parse_scenario's parser recurses per nesting level
    Scenario scenario;
    try {
      scenario = parse_scenario(text, source);
    } catch (const nlohmann::json::exception& e) { // e.g. "1e999": parse_scenario lets the overflow through
      throw InputError(source + ": malformed JSON: " + e.what());
    }
    const ConstraintSet set = resolve_scenario(scenario, V);
    // A scenario's soft vertices are those of its weighted handles: the drag moves them all.
    out.soft = {set.soft, std::vector<char>(static_cast<std::size_t>(set.soft.vertices.size()), 1)};
    // resolve_scenario lists the fixed vertices first; their count is that of the fixed part alone.
    Eigen::Index fixed_count = 0;
    if (!scenario.fixed.empty()) {
      Scenario fixed_only = scenario;
      fixed_only.handles.clear();
      fixed_count = resolve_scenario(fixed_only, V).fixed.size();
    }
    out.fixed = set.fixed.head(fixed_count);
    out.handle = set.fixed.tail(set.fixed.size() - fixed_count);
    out.targets = set.targets;
    out.warnings = set.warnings;
    return out;
  }
  std::istringstream in(text);
  const ConstraintSet set =
      parse_constraints(in, source, static_cast<int>(V.rows()), static_cast<int>(F.rows()));
  out.soft.soft = set.soft;
  for (Eigen::Index k = 0; k < set.soft.vertices.size(); ++k)
    out.soft.dragged.push_back(set.soft.vertex_targets.row(k) != V.row(set.soft.vertices[k]) ? 1 : 0);
  std::vector<Eigen::Index> fixed_rows, handle_rows;
  for (Eigen::Index i = 0; i < set.fixed.size(); ++i)
    (set.targets.row(i) == V.row(set.fixed[i]) ? fixed_rows : handle_rows).push_back(i);
  out.fixed.resize(static_cast<Eigen::Index>(fixed_rows.size()));
  out.handle.resize(static_cast<Eigen::Index>(handle_rows.size()));
  out.targets.resize(set.fixed.size(), 3);
  Eigen::Index row = 0;
  for (const Eigen::Index i : fixed_rows) {
    out.fixed[row] = set.fixed[i];
    out.targets.row(row++) = set.targets.row(i);
  }
  for (const Eigen::Index i : handle_rows) {
    out.handle[row - out.fixed.size()] = set.fixed[i];
    out.targets.row(row++) = set.targets.row(i);
  }
  out.warnings = set.warnings;
  return out;
}

} // namespace iarap::serve
