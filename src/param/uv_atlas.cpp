#include "iarap/param/uv_atlas.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/mesh/validate.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/boundary_loops.h"
#include "iarap/param/disk_mesh.h"

#include "chart_packing.h"
#include "chart_segmentation.h"
#include "uv_overlap.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace iarap {

namespace {

using param_detail::ChartMesh;

void check_atlas_options(const AtlasOptions& options) {
  if (!(options.max_normal_angle > 0 && options.max_normal_angle <= 180))
    throw InputError("max_normal_angle must lie in (0, 180] degrees; got " +
                     std::to_string(options.max_normal_angle));
  if (!(options.target_distortion > 0) || !std::isfinite(options.target_distortion))
    throw InputError("target_distortion must be a finite number > 0; got " +
                     std::to_string(options.target_distortion));
  if (options.min_chart_faces < 1)
    throw InputError("min_chart_faces must be >= 1; got " + std::to_string(options.min_chart_faces));
  if (options.texture_size < 16 || options.texture_size > 16384)
    throw InputError("texture_size must lie in 16..16384 texels; got " +
                     std::to_string(options.texture_size));
  if (!(options.padding >= 0 && options.padding < options.texture_size / 2.0))
    throw InputError("padding must lie in [0, texture_size / 2) texels; got " +
                     std::to_string(options.padding));
  if (options.max_rounds < 0)
    throw InputError("max_rounds must be >= 0; got " + std::to_string(options.max_rounds));
  if (options.param.pins.size() > 0)
    throw InputError(
        "pins do not apply to an atlas (each chart is flattened on its own); parameterize a disk "
        "with pins instead");
}

// The mesh must be an oriented manifold for its charts to be disks; what check_mesh finds otherwise
// (non-manifold edges or vertices, inconsistent orientation, bad indices or coordinates) is refused.
void check_atlas_mesh(const MeshReport& check) {
  if (!check.usable()) {
    std::string message = "the mesh cannot be cut into disk charts without a repair:";
    for (const std::string& error : check.errors) message += "\n  " + error;
    throw TopologyError(message + "\n(repair_mesh / `iarap repair` splits non-manifold vertices and "
                                  "re-orients faces)");
  }
}

// One chart and its flattening.
struct ChartMap {
  std::vector<int> faces;    // global face indices
  std::vector<int> vertices; // sorted global vertex indices; the local index of a vertex is its rank
  Eigen::MatrixXi F;         // the faces in local indices
  Eigen::MatrixXd UV;        // #vertices x 2, mesh units
  AtlasChart summary;
  bool boundary_crosses = false;

  int local(int v) const {
    return static_cast<int>(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
  }
};

ChartMap flatten_chart(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, std::vector<int> faces,
                       const ParamOptions& options, const ChartMesh& mesh) {
  ChartMap chart;
  chart.faces = std::move(faces);
  for (int f : chart.faces)
    for (int k = 0; k < 3; ++k) chart.vertices.push_back(F(f, k));
  std::sort(chart.vertices.begin(), chart.vertices.end());
  chart.vertices.erase(std::unique(chart.vertices.begin(), chart.vertices.end()), chart.vertices.end());
  Eigen::MatrixXd Vc(static_cast<Eigen::Index>(chart.vertices.size()), 3);
  for (std::size_t i = 0; i < chart.vertices.size(); ++i)
    Vc.row(static_cast<Eigen::Index>(i)) = V.row(chart.vertices[i]);
  Eigen::MatrixXi Fc(static_cast<Eigen::Index>(chart.faces.size()), 3);
  for (std::size_t i = 0; i < chart.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) Fc(static_cast<Eigen::Index>(i), k) = chart.local(F(chart.faces[i], k));
  const ParamResult result = arap_parameterize(Vc, Fc, options);
  chart.F = Fc;
  chart.UV = result.UV;
  AtlasChart& s = chart.summary;
  s.faces = static_cast<int>(Fc.rows());
  s.vertices = static_cast<int>(Vc.rows());
  for (int f : chart.faces) s.area += mesh.area(f);
  s.energy = result.report.distortion.energy;
  s.distortion = s.energy / s.area;
  s.flipped = result.report.distortion.flipped;
  s.iterations = result.report.solve.iterations;
  const std::vector<std::vector<int>> loops = boundary_loops(Fc, static_cast<int>(Vc.rows()));
  chart.boundary_crosses = param_detail::loop_crosses_itself(chart.UV, loops.front());
  return chart;
}

std::vector<std::vector<int>> faces_by_chart(const std::vector<int>& label, int charts) {
  std::vector<std::vector<int>> faces(static_cast<std::size_t>(charts));
  for (std::size_t f = 0; f < label.size(); ++f)
    if (label[f] >= 0) faces[static_cast<std::size_t>(label[f])].push_back(static_cast<int>(f));
  return faces;
}

// Flattens the charts, then splits those whose boundary crosses itself and, for up to max_rounds rounds,
// those whose distortion exceeds the target (if both halves can keep min_chart_faces), and flattens the
// parts. Splitting on overlap goes on until none is left: a chart of one face cannot overlap itself.
std::vector<ChartMap> flatten_charts(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const ChartMesh& mesh, const AtlasOptions& options, int charts,
                                     std::vector<int>& label, AtlasReport& report) {
  std::vector<ChartMap> maps;
  std::vector<char> dirty(static_cast<std::size_t>(charts), 1);
  for (int round = 0;; ++round) {
    const std::vector<std::vector<int>> faces = faces_by_chart(label, charts);
    maps.resize(static_cast<std::size_t>(charts));
    for (std::size_t c = 0; c < maps.size(); ++c)
      if (dirty[c]) maps[c] = flatten_chart(V, F, faces[c], options.param, mesh);
    std::vector<int> split;
    for (std::size_t c = 0; c < maps.size(); ++c) {
      const ChartMap& map = maps[c];
      if (map.boundary_crosses && map.summary.faces >= 2) {
        split.push_back(static_cast<int>(c));
        ++report.splits_for_overlap;
      } else if (round < options.max_rounds && map.summary.distortion > options.target_distortion &&
                 map.summary.faces >= 2 * options.min_chart_faces) {
        split.push_back(static_cast<int>(c));
        ++report.splits_for_distortion;
      }
    }
    if (split.empty()) break;
    std::fill(dirty.begin(), dirty.end(), 0);
    for (int c : split) {
      charts = param_detail::split_chart(mesh, c, faces[static_cast<std::size_t>(c)], charts, label);
      dirty[static_cast<std::size_t>(c)] = 1;
      dirty.resize(static_cast<std::size_t>(charts), 1);
    }
  }
  return maps;
}

double seam_length(const Eigen::MatrixXd& V, const ChartMesh& mesh, const std::vector<int>& label) {
  double length = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int g = mesh.neighbour(f, k);
      if (g > f && label[static_cast<std::size_t>(g)] != label[static_cast<std::size_t>(f)])
        length += (V.row(mesh.F(f, (k + 1) % 3)) - V.row(mesh.F(f, (k + 2) % 3))).norm();
    }
  return length;
}

} // namespace

ParamOptions default_atlas_param_options() {
  ParamOptions options;
  options.solve.tolerance = 1e-4;
  return options;
}

UvAtlas uv_atlas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const AtlasOptions& options) {
  const auto total_start = Clock::now();
  check_atlas_options(options);
  check_param_arrays(V, F);
  const MeshReport check = check_mesh(V, F);
  check_atlas_mesh(check);
  UvAtlas atlas;
  AtlasReport& report = atlas.report;

  auto phase_start = Clock::now();
  std::vector<int> label(static_cast<std::size_t>(F.rows()), -2); // open for segment_charts
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (is_degenerate_face(V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)), check.bbox_diagonal)) {
      label[static_cast<std::size_t>(f)] = -1;
      ++report.degenerate_faces;
    }
  const ChartMesh mesh = param_detail::chart_mesh(V, F);
  const int charts = param_detail::segment_charts(mesh, options.max_normal_angle, options.min_chart_faces,
                                                  label, report.merged_small_charts);
  if (charts == 0) throw InputError("every face of the mesh is degenerate (no area): nothing to flatten");
  report.segment_ms = ms_since(phase_start);

  phase_start = Clock::now();
  const std::vector<ChartMap> maps = flatten_charts(V, F, mesh, options, charts, label, report);
  report.flatten_ms = ms_since(phase_start);

  phase_start = Clock::now();
  std::vector<Eigen::MatrixXd> chart_uv;
  std::vector<Eigen::MatrixXi> chart_faces;
  for (const ChartMap& map : maps) {
    chart_uv.push_back(map.UV);
    chart_faces.push_back(map.F);
  }
  const param_detail::ChartPacking packing =
      param_detail::pack_charts(chart_uv, chart_faces, options.texture_size, options.padding);
  atlas.corner_uv.resize(3 * F.rows(), 2);
  Eigen::MatrixXd any_uv =
      Eigen::MatrixXd::Constant(V.rows(), 2, NAN); // a UV of each vertex, for degenerate faces
  for (std::size_t c = 0; c < maps.size(); ++c) {
    const ChartMap& map = maps[c];
    const param_detail::ChartPlacement& place = packing.placements[c];
    for (int f : map.faces)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d uv =
            packing.scale * (place.rotation * map.UV.row(map.local(F(f, k))).transpose()) + place.translation;
        atlas.corner_uv.row(3 * f + k) = uv.cwiseMax(0).cwiseMin(1).transpose(); // rounding at the border
        any_uv.row(F(f, k)) = atlas.corner_uv.row(3 * f + k);
      }
    report.charts.push_back(map.summary);
    report.energy += map.summary.energy;
    report.area += map.summary.area;
  }
  atlas.chart = Eigen::Map<const Eigen::VectorXi>(label.data(), static_cast<Eigen::Index>(label.size()));
  std::vector<bool> use(static_cast<std::size_t>(F.rows()), true);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (label[static_cast<std::size_t>(f)] < 0) {
      use[static_cast<std::size_t>(f)] = false;
      Eigen::RowVector2d point = Eigen::RowVector2d::Constant(options.padding / options.texture_size / 2);
      for (int k = 2; k >= 0; --k)
        if (!std::isnan(any_uv(F(f, k), 0))) point = any_uv.row(F(f, k));
      for (int k = 0; k < 3; ++k) atlas.corner_uv.row(3 * f + k) = point;
      continue;
    }
    const Eigen::RowVector2d a = atlas.corner_uv.row(3 * f), b = atlas.corner_uv.row(3 * f + 1),
                             c = atlas.corner_uv.row(3 * f + 2);
    const double area = ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) / 2;
    if (!(area > 0)) ++report.flipped;
    report.packing_efficiency += area; // the atlas's UV area: of the unit square
  }
  report.distortion = report.energy / report.area;
  report.seam_length = seam_length(V, mesh, label);
  for (const ChartMap& map : maps) report.boundary_overlaps += map.boundary_crosses;
  report.overlap_ratio =
      param_detail::rasterized_overlap(atlas.corner_uv, use, std::min(options.texture_size, 4096));
  report.pack_ms = ms_since(phase_start);
  report.total_ms = ms_since(total_start);
  return atlas;
}

} // namespace iarap
