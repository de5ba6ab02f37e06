#include "mesh_report_json.h"

#include "common/explain_error.h"

#include <algorithm>

namespace iarap::cli {

nlohmann::json mesh_report_json(const MeshReport& report) {
  nlohmann::json j;
  j["vertices"] = report.vertices;
  j["faces"] = report.faces;
  j["components"] = report.components;
  j["boundary_loops"] = report.boundary_loops;
  j["genus"] = report.genus ? nlohmann::json(*report.genus) : nlohmann::json(nullptr);
  j["orientable"] = report.orientable();
  j["non_orientable_components"] = report.non_orientable_components;
  j["non_manifold_edges"] = report.non_manifold_edges;
  j["non_manifold_vertices"] = report.non_manifold_vertices;
  j["zero_area_faces"] = report.zero_area_faces;
  j["unreferenced_vertices"] = report.unreferenced_vertices;
  j["non_delaunay_edges"] = report.non_delaunay_edges;
  j["inconsistently_oriented_edges"] = report.inconsistently_oriented_edges;
  j["repeated_vertex_faces"] = report.repeated_vertex_faces;
  j["out_of_range_indices"] = report.out_of_range_indices;
  j["non_finite_coordinates"] = report.non_finite_coordinates;
  j["coincident_vertices"] = report.coincident_vertices;
  j["edges"] = report.edges;
  j["boundary_edges"] = report.boundary_edges;
  j["bbox_diagonal"] = report.bbox_diagonal;
  j["errors"] = name_repair(report.errors, deform_repair_flag);
  j["warnings"] = name_repair(report.warnings, deform_repair_flag);
  j["usable"] = report.usable();
  return j;
}

nlohmann::json intrinsic_summary_json(const IntrinsicDelaunay& intrinsic) {
  const auto& t = intrinsic.triangulation;
  const auto& start = intrinsic.segments.edge_start;
  const Eigen::Index edges = t.E.rows();
  int max_per_edge = 0;
  for (Eigen::Index e = 0; e + 1 < start.size(); ++e)
    max_per_edge = std::max(max_per_edge, start(e + 1) - start(e));
  const auto segments = intrinsic.segments.edge.size();
  nlohmann::json j;
  j["flips"] = t.flips;
  j["non_delaunay_before"] = t.non_delaunay_before;
  j["non_delaunay_after"] = t.non_delaunay_after;
  j["mollify_delta"] = t.mollify_delta;
  j["intrinsic_edges"] = edges;
  j["segments"] = segments;
  j["segments_per_edge"] = edges > 0 ? static_cast<double>(segments) / static_cast<double>(edges) : 0.0;
  j["max_segments_per_edge"] = max_per_edge;
  return j;
}

} // namespace iarap::cli
