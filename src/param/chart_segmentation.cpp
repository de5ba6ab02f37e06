#include "chart_segmentation.h"

#include "iarap/mesh/edge_topology.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <queue>
#include <unordered_map>

namespace iarap::param_detail {

namespace {

constexpr int open_label = -2;
// A chart may not wrap around a vertex left on its boundary by more than a full turn: a free boundary
// flattened close to an isometry would fold over itself there (a saddle vertex, angle sum above 2 pi).
constexpr double max_boundary_angle = 2 * M_PI;

// Charts growing at once over the faces labelled `open`, each kept a topological disk.
class ChartGrowth {
public:
  ChartGrowth(const ChartMesh& mesh, std::vector<int>& label, int open, GrowthCost cost, double min_cos)
      : mesh_(mesh), label_(label), open_(open), cost_(cost), min_cos_(min_cos) {}

  // Puts face f's polygon into chart c (a seed, or faces the chart already had) and queues the open faces
  // next to it.
  void add_face(int c, int f) {
    Chart& chart = charts_[c];
    if (chart.faces == 0) chart.seed = mesh_.centroid.row(f).transpose();
    const int* polygon = mesh_.polygon_begin(f);
    const int size = mesh_.polygon_size(f);
    for (int i = 0; i < size; ++i) {
      const int g = polygon[i];
      ++chart.faces;
      added_.push_back(g);
      label_[static_cast<std::size_t>(g)] = c;
      chart.normal_sum += mesh_.area(g) * mesh_.normal.row(g).transpose();
      for (int k = 0; k < 3; ++k) chart.vertex_angle[mesh_.F(g, k)] += mesh_.angle(g, k);
    }
    for (int i = 0; i < size; ++i)
      for (int k = 0; k < 3; ++k) {
        const int h = mesh_.neighbour(polygon[i], k);
        if (h >= 0 && label_[static_cast<std::size_t>(h)] == open_) queue_.push({cost(chart, h), h, c});
      }
  }

  void run() {
    while (!queue_.empty()) {
      const Candidate next = queue_.top();
      queue_.pop();
      if (label_[static_cast<std::size_t>(next.face)] != open_) continue;
      Chart& chart = charts_[next.chart];
      if (polygon_normal(next.face).dot(chart.normal_sum.normalized()) < min_cos_) continue;
      if (keeps_disk(chart, next.chart, next.face)) add_face(next.chart, next.face);
    }
  }

  const std::vector<int>& added() const { return added_; } // every face add_face took, in order

private:
  struct Chart {
    int faces = 0;
    Eigen::Vector3d seed = Eigen::Vector3d::Zero(), normal_sum = Eigen::Vector3d::Zero();
    std::unordered_map<int, double> vertex_angle; // the chart's angle at each of its vertices
  };
  struct Candidate {
    double cost;
    int face, chart;
    bool operator<(const Candidate& other) const { return cost > other.cost; } // smallest cost on top
  };

  double cost(const Chart& chart, int f) const {
    if (cost_ == GrowthCost::Distance) return (mesh_.centroid.row(f).transpose() - chart.seed).norm();
    return 1 - mesh_.normal.row(f).dot(chart.normal_sum.normalized());
  }

  Eigen::Vector3d polygon_normal(int f) const {
    if (mesh_.polygon_size(f) == 1) return mesh_.normal.row(f).transpose();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const int* polygon = mesh_.polygon_begin(f);
    for (int i = 0; i < mesh_.polygon_size(f); ++i)
      sum += mesh_.area(polygon[i]) * mesh_.normal.row(polygon[i]).transpose();
    return sum.normalized();
  }

  // Adding a polygon (a disk) to a disk chart leaves a disk when the edges they share form one path along
  // the polygon's boundary, not all of it, and the polygon's other vertices are new to the chart: the
  // path's inner vertices become inner vertices of the chart, its ends stay on the boundary. For a
  // triangle: one shared edge with the third vertex new (an ear), or two (a notch, their common vertex
  // becomes inner); a third vertex already in the chart would pinch it, three shared edges would close it.
  bool keeps_disk(const Chart& chart, int c, int f) const {
    const int* polygon = mesh_.polygon_begin(f);
    const int size = mesh_.polygon_size(f);
    for (int i = 0; i < size; ++i)
      if (label_[static_cast<std::size_t>(polygon[i])] != open_) return false;
    boundary_.clear();
    for (int i = 0; i < size; ++i)
      for (int k = 0; k < 3; ++k) {
        const int g = polygon[i], h = mesh_.neighbour(g, k);
        if (h >= 0 &&
            mesh_.polygon[static_cast<std::size_t>(h)] == mesh_.polygon[static_cast<std::size_t>(g)])
          continue;
        boundary_.push_back({mesh_.F(g, (k + 1) % 3), mesh_.F(g, (k + 2) % 3),
                             h >= 0 && label_[static_cast<std::size_t>(h)] == c});
      }
    // In cyclic order: each next edge starts where the last ended. A boundary that is not one simple cycle
    // (a polygon pinched at a vertex) is refused.
    const std::size_t m = boundary_.size();
    if (m < 3) return false; // no boundary to share (a closed group) or none a polygon can have
    for (std::size_t i = 0; i + 1 < m; ++i) {
      std::size_t j = i + 1;
      while (j < m && boundary_[j].from != boundary_[i].to) ++j;
      if (j == m) return false;
      std::swap(boundary_[i + 1], boundary_[j]);
    }
    if (boundary_.back().to != boundary_.front().from) return false;
    int shared = 0, runs = 0;
    for (std::size_t i = 0; i < m; ++i) {
      shared += boundary_[i].shared;
      runs += boundary_[i].shared && !boundary_[(i + m - 1) % m].shared;
    }
    if (shared == 0 || shared == static_cast<int>(m) || runs != 1) return false;
    // Each boundary vertex: inner after the addition (between two shared edges), on the shared path's ends,
    // or off the path (must be new to the chart). The chart may not wrap around a vertex left on its
    // boundary by more than max_boundary_angle, which a flattening with a free boundary would have to fold
    // over itself near a saddle (angle sum above 2 pi).
    for (std::size_t i = 0; i < m; ++i) {
      const bool after_shared = boundary_[(i + m - 1) % m].shared, before_shared = boundary_[i].shared;
      if (after_shared && before_shared) continue; // becomes inner
      const int v = boundary_[i].from;
      const auto it = chart.vertex_angle.find(v);
      if (!after_shared && !before_shared && it != chart.vertex_angle.end()) return false;
      double angle = it == chart.vertex_angle.end() ? 0 : it->second;
      for (int p = 0; p < size; ++p)
        for (int k = 0; k < 3; ++k)
          if (mesh_.F(polygon[p], k) == v) angle += mesh_.angle(polygon[p], k);
      if (angle > max_boundary_angle) return false;
    }
    return true;
  }

  const ChartMesh& mesh_;
  std::vector<int>& label_;
  int open_;
  GrowthCost cost_;
  double min_cos_;
  std::unordered_map<int, Chart> charts_;
  std::priority_queue<Candidate> queue_;
  std::vector<int> added_;
  // keeps_disk's scratch: the polygon's boundary edges (from, to) in the faces' orientation, and whether the
  // chart lies across.
  struct BoundaryEdge {
    int from, to;
    bool shared;
  };
  mutable std::vector<BoundaryEdge> boundary_;
};

// Grows new charts one at a time from open faces until none is left: each from an open face next to the
// previous chart if there is one (charts then tile the surface front by front), else the first open face.
int grow_remaining(const ChartMesh& mesh, std::vector<int>& label, int open, GrowthCost cost, double min_cos,
                   int next_id) {
  std::size_t scan = 0;
  std::vector<int> front;
  while (true) {
    int seed = -1;
    while (!front.empty() && seed < 0) {
      if (label[static_cast<std::size_t>(front.back())] == open) seed = front.back();
      front.pop_back();
    }
    while (seed < 0 && scan < label.size()) {
      if (label[scan] == open) seed = static_cast<int>(scan);
      ++scan;
    }
    if (seed < 0) return next_id;
    ChartGrowth growth(mesh, label, open, cost, min_cos);
    growth.add_face(next_id, seed);
    growth.run();
    front.clear();
    for (int f : growth.added())
      for (int k = 0; k < 3; ++k) {
        const int g = mesh.neighbour(f, k);
        if (g >= 0 && label[static_cast<std::size_t>(g)] == open) front.push_back(g);
      }
    ++next_id;
  }
}

// Renumbers the labels >= 0 to 0..n-1 in order of first appearance; returns n.
int compact_labels(std::vector<int>& label) {
  std::unordered_map<int, int> id;
  for (int& l : label)
    if (l >= 0) l = id.emplace(l, static_cast<int>(id.size())).first->second;
  return static_cast<int>(id.size());
}

// The face of `faces` farthest from face `from` whose polygon is not skip_polygon (-1: any).
int farthest_face(const ChartMesh& mesh, const std::vector<int>& faces, int from, int skip_polygon) {
  int best = -1;
  double best_distance = -1;
  for (int f : faces) {
    const double d = (mesh.centroid.row(f) - mesh.centroid.row(from)).squaredNorm();
    if (d > best_distance && mesh.polygon[static_cast<std::size_t>(f)] != skip_polygon)
      best_distance = d, best = f;
  }
  return best;
}

// Groups the faces by polygon: each face with an id >= 0 joins its polygon, the others are alone.
void group_polygons(ChartMesh& mesh, const std::vector<int>& polygon_of_face) {
  const auto faces = static_cast<std::size_t>(mesh.F.rows());
  mesh.polygon.resize(faces);
  std::unordered_map<int, int> id; // given id -> polygon
  int polygons = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    const int given = polygon_of_face.empty() ? -1 : polygon_of_face[f];
    if (given < 0) {
      mesh.polygon[f] = polygons++;
    } else {
      const auto [it, added] = id.emplace(given, polygons);
      polygons += added;
      mesh.polygon[f] = it->second;
    }
  }
  mesh.polygon_first.assign(static_cast<std::size_t>(polygons) + 1, 0);
  for (int p : mesh.polygon) ++mesh.polygon_first[static_cast<std::size_t>(p) + 1];
  for (std::size_t p = 0; p < static_cast<std::size_t>(polygons); ++p)
    mesh.polygon_first[p + 1] += mesh.polygon_first[p];
  mesh.polygon_faces.resize(faces);
  std::vector<int> next(mesh.polygon_first.begin(), mesh.polygon_first.end() - 1);
  for (std::size_t f = 0; f < faces; ++f)
    mesh.polygon_faces[static_cast<std::size_t>(next[static_cast<std::size_t>(mesh.polygon[f])]++)] =
        static_cast<int>(f);
}

} // namespace

ChartMesh chart_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const std::vector<int>& polygon_of_face) {
  ChartMesh mesh;
  mesh.F = F;
  const EdgeTopology topology = edge_topology(F, static_cast<int>(V.rows()));
  mesh.neighbour.setConstant(F.rows(), 3, -1);
  mesh.normal.resize(F.rows(), 3);
  mesh.area.resize(F.rows());
  mesh.centroid.resize(F.rows(), 3);
  mesh.angle.resize(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int e = topology.FE(f, k);
      if (topology.face_count(e) == 2)
        mesh.neighbour(f, k) = topology.EF(e, 0) == f ? topology.EF(e, 1) : topology.EF(e, 0);
    }
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    mesh.area(f) = n.norm() / 2;
    mesh.normal.row(f) = mesh.area(f) > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    mesh.centroid.row(f) = (a + b + c) / 3;
    const Eigen::Vector3d corner[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = corner[(k + 1) % 3] - corner[k], e2 = corner[(k + 2) % 3] - corner[k];
      mesh.angle(f, k) = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
    }
  }
  group_polygons(mesh, polygon_of_face);
  return mesh;
}

int segment_charts(const ChartMesh& mesh, double max_normal_angle, int min_faces, std::vector<int>& label,
                   int& merged) {
  const double pi = std::acos(-1.0);
  const double min_cos = std::cos(max_normal_angle * pi / 180);
  const int grown = grow_remaining(mesh, label, open_label, GrowthCost::Normal, min_cos, 0);
  // Small charts: dissolved, then their faces taken by the neighbouring charts without the angle bound.
  std::vector<int> size(static_cast<std::size_t>(grown), 0);
  for (int l : label)
    if (l >= 0) ++size[static_cast<std::size_t>(l)];
  merged = 0;
  for (int s : size)
    if (s < min_faces) ++merged;
  if (merged > 0 && merged < grown) {
    for (int& l : label)
      if (l >= 0 && size[static_cast<std::size_t>(l)] < min_faces) l = open_label;
    ChartGrowth growth(mesh, label, open_label, GrowthCost::Normal, -2);
    for (std::size_t f = 0; f < label.size(); ++f) // each kept polygon once, from its first face
      if (label[f] >= 0 && *mesh.polygon_begin(static_cast<int>(f)) == static_cast<int>(f))
        growth.add_face(label[f], static_cast<int>(f));
    growth.run();
    grow_remaining(mesh, label, open_label, GrowthCost::Normal, -2, grown);
  } else {
    merged = 0;
  }
  return compact_labels(label);
}

int split_chart(const ChartMesh& mesh, int id, const std::vector<int>& faces, int next_id,
                std::vector<int>& label, int parts) {
  constexpr int splitting = -3;
  for (int f : faces) label[static_cast<std::size_t>(f)] = splitting;
  // Seeds by farthest-point sampling: the face farthest from the first, then each next the face farthest
  // from every seed so far (for two parts: the farthest from the first seed), each in a polygon of its own.
  std::vector<int> seeds{farthest_face(mesh, faces, faces.front(), -1)};
  std::vector<double> nearest(faces.size(), INFINITY);
  std::vector<char> seed_polygon(static_cast<std::size_t>(mesh.polygon_first.size()), 0);
  while (static_cast<int>(seeds.size()) < parts) {
    const int last = seeds.back();
    seed_polygon[static_cast<std::size_t>(mesh.polygon[static_cast<std::size_t>(last)])] = 1;
    int best = -1;
    double best_distance = -1;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const int f = faces[i];
      nearest[i] = std::min(nearest[i], (mesh.centroid.row(f) - mesh.centroid.row(last)).squaredNorm());
      if (nearest[i] > best_distance &&
          !seed_polygon[static_cast<std::size_t>(mesh.polygon[static_cast<std::size_t>(f)])])
        best_distance = nearest[i], best = f;
    }
    if (best < 0) break;
    seeds.push_back(best);
  }
  ChartGrowth growth(mesh, label, splitting, GrowthCost::Distance, -2);
  growth.add_face(id, seeds.front());
  for (std::size_t i = 1; i < seeds.size(); ++i) growth.add_face(next_id++, seeds[i]);
  growth.run();
  return grow_remaining(mesh, label, splitting, GrowthCost::Distance, -2, next_id);
}

} // namespace iarap::param_detail
