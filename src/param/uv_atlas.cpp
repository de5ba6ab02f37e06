#include "iarap/param/uv_atlas.h"

#include "iarap/core/errors.h"
#include "iarap/core/stopwatch.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/mesh/validate.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/boundary_loops.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/lscm.h"

#include "arap_parameterize_disk.h"
#include "chart_packing.h"
#include "chart_segmentation.h"
#include "uv_overlap.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <unordered_map>

namespace iarap {

namespace {

using param_detail::ChartMesh;

// A chart whose boundary crosses itself is split into one part per overlap_split_faces faces, 2 to
// max_overlap_split_parts (the ogre: 343K faces flattened over 15 rounds with halves, 227K over 10 with
// these; 588 charts to 627, packing 0.662 to 0.651).
constexpr int overlap_split_faces = 300;
constexpr int max_overlap_split_parts = 16;

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
  // A chart's boundary on a circle maps curved patches far from isometry (the bunny: 339 charts split for
  // distortion, 1.12 left) and packs poorly: an atlas frees every chart's boundary.
  if (options.param.boundary != ParamBoundary::Free)
    throw InputError("boundary " + param_boundary_name(options.param.boundary) +
                     " does not apply to an atlas (each chart's boundary is free); flatten a disk with it "
                     "instead");
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

void check_atlas_input(const AtlasInput& input, Eigen::Index faces) {
  const auto expect = static_cast<std::size_t>(faces);
  if (!input.polygon_of_face.empty() && input.polygon_of_face.size() != expect)
    throw InputError("polygon_of_face must have one id per face (" + std::to_string(faces) + "); got " +
                     std::to_string(input.polygon_of_face.size()));
  if (!input.charts.empty() && input.charts.size() != expect)
    throw InputError("charts must have one id per face (" + std::to_string(faces) + "); got " +
                     std::to_string(input.charts.size()));
  for (std::size_t f = 0; f < input.charts.size(); ++f)
    if (input.charts[f] < 0)
      throw InputError("face " + std::to_string(f) + " has chart id " + std::to_string(input.charts[f]) +
                       "; given chart ids must be >= 0");
  if (input.corner_uv.size() > 0) {
    if (input.charts.empty()) throw InputError("corner_uv is the layout of given charts: give charts too");
    if (input.corner_uv.rows() != 3 * faces || input.corner_uv.cols() != 2 || !input.corner_uv.allFinite())
      throw InputError("corner_uv must be (3 #F) x 2 = " + std::to_string(3 * faces) +
                       " x 2 finite UVs; got " + std::to_string(input.corner_uv.rows()) + " x " +
                       std::to_string(input.corner_uv.cols()));
  }
}

// The caller's charts as labels 0..n-1 in order of first appearance (faces labelled -1, degenerate, stay
// so); returns n.
int given_charts(const std::vector<int>& charts, std::vector<int>& label) {
  std::unordered_map<int, int> id;
  for (std::size_t f = 0; f < label.size(); ++f)
    if (label[f] != -1) label[f] = id.emplace(charts[f], static_cast<int>(id.size())).first->second;
  return static_cast<int>(id.size());
}

// One chart and its flattening.
struct ChartMap {
  std::vector<int> faces;    // global face indices
  std::vector<int> vertices; // sorted global vertex indices; the local index of a vertex is its rank
  Eigen::MatrixXi F;         // the faces in local indices
  Eigen::MatrixXd UV;        // #vertices x 2, mesh units
  AtlasChart summary;
  int polygons = 0;              // distinct polygons among its faces (a split needs two)
  bool boundary_crosses = false; // of the final map, or of the start when start_crosses
  bool start_crosses = false;    // its LSCM start crossed itself: split before the solve, not flattened

  int local(int v) const {
    return static_cast<int>(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
  }
};

// How flatten_chart starts a chart's flattening.
struct ChartStart {
  const Eigen::MatrixXd* corner_uv = nullptr; // AtlasInput::corner_uv for a chart given by the caller
  bool check_lscm = false; // compute the LSCM start here and split the chart if it crosses itself
  int given_id = -1;       // the caller's chart (for errors), -1 for the atlas's own
};

// The given corner UVs of the chart's vertices, scaled so that the UV area equals the surface area (the
// scale near which an ARAP map lies); empty if they have no area.
Eigen::MatrixXd given_start(const ChartMap& chart, const Eigen::MatrixXi& F, const Eigen::MatrixXd& corner_uv,
                            double surface_area) {
  Eigen::MatrixXd UV(static_cast<Eigen::Index>(chart.vertices.size()), 2);
  for (int f : chart.faces)
    for (int k = 0; k < 3; ++k) UV.row(chart.local(F(f, k))) = corner_uv.row(3 * f + k);
  double uv_area = 0;
  for (Eigen::Index f = 0; f < chart.F.rows(); ++f) {
    const Eigen::RowVector2d a = UV.row(chart.F(f, 0)), b = UV.row(chart.F(f, 1)), c = UV.row(chart.F(f, 2));
    uv_area += ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) / 2;
  }
  if (!(uv_area > 0)) return {};
  return UV * std::sqrt(surface_area / uv_area);
}

ChartMap flatten_chart(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, std::vector<int> faces,
                       ParamOptions options, const ChartMesh& mesh, const ChartStart& start) {
  ChartMap chart;
  chart.faces = std::move(faces);
  std::vector<int> polygons;
  for (int f : chart.faces) {
    polygons.push_back(mesh.polygon[static_cast<std::size_t>(f)]);
    for (int k = 0; k < 3; ++k) chart.vertices.push_back(F(f, k));
  }
  std::sort(polygons.begin(), polygons.end());
  chart.polygons = static_cast<int>(std::unique(polygons.begin(), polygons.end()) - polygons.begin());
  std::sort(chart.vertices.begin(), chart.vertices.end());
  chart.vertices.erase(std::unique(chart.vertices.begin(), chart.vertices.end()), chart.vertices.end());
  Eigen::MatrixXd Vc(static_cast<Eigen::Index>(chart.vertices.size()), 3);
  for (std::size_t i = 0; i < chart.vertices.size(); ++i)
    Vc.row(static_cast<Eigen::Index>(i)) = V.row(chart.vertices[i]);
  Eigen::MatrixXi Fc(static_cast<Eigen::Index>(chart.faces.size()), 3);
  for (std::size_t i = 0; i < chart.faces.size(); ++i)
    for (int k = 0; k < 3; ++k) Fc(static_cast<Eigen::Index>(i), k) = chart.local(F(chart.faces[i], k));
  chart.F = Fc;
  AtlasChart& s = chart.summary;
  s.faces = static_cast<int>(Fc.rows());
  s.vertices = static_cast<int>(Vc.rows());
  for (int f : chart.faces) s.area += mesh.area(f);
  const auto chart_start = Clock::now();
  const double scale = normalizing_scale(Vc);
  DiskMesh disk;
  if (start.given_id < 0) {
    disk = prepare_chart_disk(Vc / scale, Fc);
  } else {
    try {
      disk = prepare_disk(Vc / scale, Fc);
    } catch (const TopologyError& e) {
      throw TopologyError("chart " + std::to_string(start.given_id) + " of the texture seams (" +
                          std::to_string(s.faces) + " triangles, face " +
                          std::to_string(chart.faces.front()) + " among them): " + e.what());
    }
  }
  if (start.corner_uv) {
    options.initial_uv = given_start(chart, F, *start.corner_uv, s.area);
  } else if (start.check_lscm) {
    // The ARAP solve's own start (the same LSCM map of the same disk): when its boundary already crosses
    // itself the solve is skipped and the chart split, since ARAP's boundary mostly keeps LSCM's shape.
    const Eigen::MatrixXd lscm_map = lscm(disk);
    if (chart.polygons >= 2 && param_detail::loop_crosses_itself(lscm_map, disk.boundary)) {
      chart.boundary_crosses = chart.start_crosses = true;
      return chart;
    }
    options.initial_uv = lscm_map * scale;
  }
  const ParamResult result = param_detail::arap_parameterize_disk(disk, scale, options, chart_start);
  chart.UV = result.UV;
  s.energy = result.report.distortion.energy;
  s.distortion = s.energy / s.area;
  s.flipped = result.report.distortion.flipped;
  s.iterations = result.report.solve.iterations;
  s.started_from_input = start.corner_uv && result.report.initial_uv_used ? 1 : 0;
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

// flatten_chart for the charts marked dirty, in parallel (one chart per thread: the maps do not depend on
// the thread count); an exception of any chart is rethrown after the loop.
void flatten_dirty(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const ChartMesh& mesh,
                   const ParamOptions& param, const std::vector<std::vector<int>>& faces,
                   const std::vector<char>& dirty, const std::vector<ChartStart>& starts,
                   std::vector<ChartMap>& maps) {
  std::vector<int> todo;
  for (std::size_t c = 0; c < dirty.size(); ++c)
    if (dirty[c]) todo.push_back(static_cast<int>(c));
  // Largest first, so that the threads end together.
  std::stable_sort(todo.begin(), todo.end(), [&faces](int a, int b) {
    return faces[static_cast<std::size_t>(a)].size() > faces[static_cast<std::size_t>(b)].size();
  });
  std::vector<std::exception_ptr> errors(todo.size());
  const auto n = static_cast<std::ptrdiff_t>(todo.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::size_t>(todo[static_cast<std::size_t>(i)]);
    // Everything inside on this one thread (this task's setting only): the factorizations' BLAS too, whose
    // thread count would otherwise follow the caller's and change the sums' order with it.
    set_thread_count(1);
    try {
      maps[c] = flatten_chart(V, F, faces[c], param, mesh, starts[c]);
    } catch (...) {
      errors[static_cast<std::size_t>(i)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

// Flattens the charts, then splits those whose boundary (or LSCM start) crosses itself and, for up to
// max_rounds rounds, those whose distortion exceeds the target (if both halves can keep
// min_chart_faces), and flattens the parts. Splitting on overlap goes on until none is left: a chart of
// one polygon is not split (nor crosses itself, for a triangle).
std::vector<ChartMap> flatten_charts(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const ChartMesh& mesh, const AtlasOptions& options,
                                     const AtlasInput& input, int charts, std::vector<int>& label,
                                     AtlasReport& report) {
  const bool given = !input.charts.empty();
  const bool lscm_start = options.param.init == ParamInit::Lscm &&
                          options.param.boundary == ParamBoundary::Free && options.param.pins.size() == 0;
  std::vector<ChartMap> maps;
  std::vector<char> dirty(static_cast<std::size_t>(charts), 1);
  std::vector<ChartStart> starts(static_cast<std::size_t>(charts));
  for (std::size_t c = 0; c < starts.size(); ++c) {
    starts[c].check_lscm = lscm_start;
    if (given) starts[c].given_id = static_cast<int>(c);
    if (given && input.corner_uv.size() > 0) starts[c].corner_uv = &input.corner_uv;
  }
  for (int round = 0;; ++round) {
    const std::vector<std::vector<int>> faces = faces_by_chart(label, charts);
    maps.resize(static_cast<std::size_t>(charts));
    flatten_dirty(V, F, mesh, options.param, faces, dirty, starts, maps);
    std::vector<int> split;
    for (std::size_t c = 0; c < maps.size(); ++c) {
      const ChartMap& map = maps[c];
      if (map.boundary_crosses && map.polygons >= 2) {
        split.push_back(static_cast<int>(c));
        ++report.splits_for_overlap;
        report.splits_before_solve += map.start_crosses;
      } else if (!given && round < options.max_rounds && map.summary.distortion > options.target_distortion &&
                 map.summary.faces >= 2 * options.min_chart_faces && map.polygons >= 2) {
        split.push_back(static_cast<int>(c));
        ++report.splits_for_distortion;
      }
    }
    if (split.empty()) break;
    std::fill(dirty.begin(), dirty.end(), 0);
    for (int c : split) {
      const auto& chart_faces = faces[static_cast<std::size_t>(c)];
      // A chart that crosses itself is cut into parts of about overlap_split_faces faces at once (two
      // halves kept crossing for up to 14 rounds on the ogre, each part's LSCM solved again each round).
      const int parts = maps[static_cast<std::size_t>(c)].boundary_crosses
                            ? std::clamp(static_cast<int>(chart_faces.size()) / overlap_split_faces, 2,
                                         max_overlap_split_parts)
                            : 2;
      charts = param_detail::split_chart(mesh, c, chart_faces, charts, label, parts);
      dirty[static_cast<std::size_t>(c)] = 1;
      dirty.resize(static_cast<std::size_t>(charts), 1);
      // The parts of a split chart start as the atlas's own charts (the given layout was the whole's).
      starts[static_cast<std::size_t>(c)].corner_uv = nullptr;
      starts.resize(static_cast<std::size_t>(charts), ChartStart{nullptr, lscm_start, -1});
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
  return uv_atlas(V, F, options, AtlasInput{});
}

UvAtlas uv_atlas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const AtlasOptions& options,
                 const AtlasInput& input) {
  const auto total_start = Clock::now();
  check_atlas_options(options);
  check_param_arrays(V, F);
  check_atlas_input(input, F.rows());
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
  std::vector<int> polygon_of_face = input.polygon_of_face;
  for (std::size_t f = 0; f < polygon_of_face.size(); ++f)
    if (label[f] == -1) polygon_of_face[f] = -1; // a face without an area stays out of the charts
  const ChartMesh mesh = param_detail::chart_mesh(V, F, polygon_of_face);
  const int charts = input.charts.empty() ? param_detail::segment_charts(mesh, options.max_normal_angle,
                                                                         options.min_chart_faces, label,
                                                                         report.merged_small_charts)
                                          : given_charts(input.charts, label);
  if (charts == 0) throw InputError("every face of the mesh is degenerate (no area): nothing to flatten");
  report.segment_ms = ms_since(phase_start);

  phase_start = Clock::now();
  const std::vector<ChartMap> maps = flatten_charts(V, F, mesh, options, input, charts, label, report);
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
