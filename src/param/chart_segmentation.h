// Charts that are topological disks, grown over a triangle mesh's faces (uv_atlas.h states the method).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap::param_detail {

// What growing charts reads of the mesh: per face its neighbours, unit normal, area and centroid, and the
// polygon it belongs to (the faces of one polygon join a chart together, so that the polygon keeps one UV per
// corner when it is written back).
struct ChartMesh {
  Eigen::MatrixXi F;         // #F x 3
  Eigen::MatrixXi neighbour; // #F x 3: the face across the edge opposite corner k, -1 for none
  Eigen::MatrixXd normal;    // #F x 3 unit normals (zero for a degenerate face)
  Eigen::VectorXd area;      // #F
  Eigen::MatrixXd centroid;  // #F x 3
  Eigen::MatrixXd angle;     // #F x 3: the face's angle at corner k, radians
  std::vector<int> polygon;  // #F: the polygon of each face (each face its own for a triangle mesh)
  std::vector<int>
      polygon_first; // #polygons + 1: polygon p's faces are polygon_faces[first[p] .. first[p+1])
  std::vector<int> polygon_faces;

  int polygon_size(int f) const {
    const auto p = static_cast<std::size_t>(polygon[static_cast<std::size_t>(f)]);
    return polygon_first[p + 1] - polygon_first[p];
  }
  const int* polygon_begin(int f) const {
    return polygon_faces.data() +
           polygon_first[static_cast<std::size_t>(polygon[static_cast<std::size_t>(f)])];
  }
};

// F must be an oriented manifold (every edge in at most two faces, traversed oppositely). polygon_of_face:
// empty (every face a polygon of its own) or #F polygon ids 0..n-1 (the triangles of each input polygon;
// ids < 0 make a face a polygon of its own, as degenerate faces are).
ChartMesh chart_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                     const std::vector<int>& polygon_of_face = {});

// How a growing chart ranks the faces next to it.
enum class GrowthCost {
  Normal,   // 1 - n_f . the chart's mean normal (flat charts first)
  Distance, // distance from the chart's seed face (compact charts, for splitting)
};

// Labels every face whose label is open (-2 on entry) with a chart id >= 0, charts being topological
// disks: grown one at a time from the first open face next to the previous chart (else the first open
// face), each within max_normal_angle degrees of its mean normal. Charts of fewer than min_faces faces are
// dissolved and their faces grown into neighbouring charts without the angle bound; what is still left
// forms charts of its own. Faces labelled -1 (degenerate) stay -1. Returns the number of charts; ids are
// 0..n-1. merged counts the dissolved charts.
int segment_charts(const ChartMesh& mesh, double max_normal_angle, int min_faces, std::vector<int>& label,
                   int& merged);

// Splits chart `id` (its faces `faces`, of at least two polygons) into `parts` disks grown at once from
// seeds far apart (farthest-point sampling over the face centroids, each seed in a polygon of its own),
// ranked by distance; faces none can take (the disk rule) become charts of their own. The first part keeps
// `id`, the others get next_id, next_id + 1, ...; returns the new next_id.
int split_chart(const ChartMesh& mesh, int id, const std::vector<int>& faces, int next_id,
                std::vector<int>& label, int parts = 2);

} // namespace iarap::param_detail
