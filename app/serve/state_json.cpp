#include "state_json.h"

namespace iarap::serve {
namespace {

using nlohmann::json;

// The loaded file's soft constraints: the soft vertices with their weights and whether the drag moves them
// (a weighted handle), and the count of points on faces (which keep their targets).
json soft_json(const SoftSession& session) {
  const SoftConstraintSet& soft = session.soft;
  json dragged = json::array();
  for (const char d : session.dragged) dragged.push_back(d != 0);
  return {{"vertices", std::vector<int>(soft.vertices.data(), soft.vertices.data() + soft.vertices.size())},
          {"weights", std::vector<double>(soft.vertex_weights.data(),
                                          soft.vertex_weights.data() + soft.vertex_weights.size())},
          {"dragged", dragged},
          {"face_points", soft.faces.size()},
          {"hard_face_points", soft.hard_faces.size()}};
}

} // namespace

json state_json(const ServeConfig& config, const Session& session) {
  json j;
  j["meshes"] = json::array();
  for (const auto& mesh : config.meshes) j["meshes"].push_back(mesh.name);
  j["methods"] = json::array();
  for (const ArapMethod method : all_methods) j["methods"].push_back(arap_method_name(method));
  j["limits"] = {{"max_json_bytes", config.max_json_bytes},
                 {"max_upload_bytes", config.max_upload_bytes},
                 {"max_iterations", config.max_iterations}};
  j["upload_formats"] = {"obj", "off", "ply", "stl", "mesh", "msh"};
  j["target_formats"] = {"xyz", "ply", "obj", "off", "stl"};
  j["mesh"] = nullptr;
  if (session.has_mesh()) {
    const MeshSummary& summary = session.mesh_summary();
    j["mesh"] = {{"name", summary.name},
                 {"vertices", summary.vertices},
                 {"faces", summary.faces},
                 {"tetrahedra", summary.tetrahedra},
                 {"bbox_diagonal", summary.bbox_diagonal},
                 {"notes", summary.notes},
                 {"warnings", summary.warnings}};
    const Eigen::VectorXi& fixed = session.fixed();
    const Eigen::VectorXi& handle = session.handle();
    j["fixed"] = std::vector<int>(fixed.data(), fixed.data() + fixed.size());
    j["handle"] = std::vector<int>(handle.data(), handle.data() + handle.size());
    j["rigid_groups"] = json::array();
    for (const Eigen::VectorXi& group : session.rigid_groups())
      j["rigid_groups"].push_back(std::vector<int>(group.data(), group.data() + group.size()));
    j["soft"] = soft_json(session.soft());
    j["revision"] = session.revision();
    j["target"] = nullptr;
    if (const auto& target = session.target()) {
      j["target"] = {{"name", target->name},
                     {"points", target->target.points.rows()},
                     {"faces", target->target.faces.rows()},
                     {"diagonal", target->target.diagonal}};
    }
  }
  return j;
}

json state_json(const ServeConfig& config, const SharedSession& session) {
  return session.read([&](const Session& s) { return state_json(config, s); });
}

} // namespace iarap::serve
