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

  // Puts face f into chart c (a seed, or a face the chart already had) and queues its open neighbours.
  void add_face(int c, int f) {
    Chart& chart = charts_[c];
    if (chart.faces == 0) chart.seed = mesh_.centroid.row(f).transpose();
    ++chart.faces;
    added_.push_back(f);
    label_[static_cast<std::size_t>(f)] = c;
    chart.normal_sum += mesh_.area(f) * mesh_.normal.row(f).transpose();
    for (int k = 0; k < 3; ++k) chart.vertex_angle[mesh_.F(f, k)] += mesh_.angle(f, k);
    for (int k = 0; k < 3; ++k) {
      const int g = mesh_.neighbour(f, k);
      if (g >= 0 && label_[static_cast<std::size_t>(g)] == open_) queue_.push({cost(chart, g), g, c});
    }
  }

  void run() {
    while (!queue_.empty()) {
      const Candidate next = queue_.top();
      queue_.pop();
      if (label_[static_cast<std::size_t>(next.face)] != open_) continue;
      Chart& chart = charts_[next.chart];
      if (mesh_.normal.row(next.face).dot(chart.normal_sum.normalized()) < min_cos_) continue;
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

  // Adding a triangle to a disk along one edge with its third vertex new to the disk, or along two edges
  // (their common vertex becomes inner), leaves a disk; a third vertex already in the disk would pinch it,
  // three shared edges would close it.
  bool keeps_disk(const Chart& chart, int c, int f) const {
    int shared = 0, free_corner = -1;
    for (int k = 0; k < 3; ++k) {
      const int g = mesh_.neighbour(f, k);
      if (g >= 0 && label_[static_cast<std::size_t>(g)] == c) {
        ++shared;
        free_corner = k; // the corner opposite the shared edge
      }
    }
    if (shared == 1 && chart.vertex_angle.count(mesh_.F(f, free_corner)) > 0) return false;
    if (shared != 1 && shared != 2) return false;
    // The vertices left on the chart's boundary: the chart may not wrap around one by more than
    // max_boundary_angle, which a flattening with a free boundary would have to fold over itself near a
    // saddle (angle sum above 2 pi). With two shared edges the corner opposite the open edge becomes inner.
    for (int k = 0; k < 3; ++k) {
      const bool becomes_inner = shared == 2 && k == open_corner(f, c);
      if (becomes_inner) continue;
      const auto it = chart.vertex_angle.find(mesh_.F(f, k));
      const double before = it == chart.vertex_angle.end() ? 0 : it->second;
      if (before + mesh_.angle(f, k) > max_boundary_angle) return false;
    }
    return true;
  }

  // With two edges shared with chart c, the corner between them (opposite the third, open edge).
  int open_corner(int f, int c) const {
    for (int k = 0; k < 3; ++k) {
      const int g = mesh_.neighbour(f, k);
      if (!(g >= 0 && label_[static_cast<std::size_t>(g)] == c)) return k;
    }
    return -1;
  }

  const ChartMesh& mesh_;
  std::vector<int>& label_;
  int open_;
  GrowthCost cost_;
  double min_cos_;
  std::unordered_map<int, Chart> charts_;
  std::priority_queue<Candidate> queue_;
  std::vector<int> added_;
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

int farthest_face(const ChartMesh& mesh, const std::vector<int>& faces, int from) {
  int best = faces.front();
  double best_distance = -1;
  for (int f : faces) {
    const double d = (mesh.centroid.row(f) - mesh.centroid.row(from)).squaredNorm();
    if (d > best_distance) best_distance = d, best = f;
  }
  return best;
}

} // namespace

ChartMesh chart_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
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
    for (std::size_t f = 0; f < label.size(); ++f)
      if (label[f] >= 0) growth.add_face(label[f], static_cast<int>(f));
    growth.run();
    grow_remaining(mesh, label, open_label, GrowthCost::Normal, -2, grown);
  } else {
    merged = 0;
  }
  return compact_labels(label);
}

int split_chart(const ChartMesh& mesh, int id, const std::vector<int>& faces, int next_id,
                std::vector<int>& label) {
  constexpr int splitting = -3;
  for (int f : faces) label[static_cast<std::size_t>(f)] = splitting;
  const int a = farthest_face(mesh, faces, faces.front());
  int b = farthest_face(mesh, faces, a);
  if (b == a) b = faces.front() == a ? faces.back() : faces.front(); // all centroids at one point
  ChartGrowth growth(mesh, label, splitting, GrowthCost::Distance, -2);
  growth.add_face(id, a);
  if (b != a) growth.add_face(next_id++, b);
  growth.run();
  return grow_remaining(mesh, label, splitting, GrowthCost::Distance, -2, next_id);
}

} // namespace iarap::param_detail
