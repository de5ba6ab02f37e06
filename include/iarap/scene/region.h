// Vertex selection rules of scenarios: index lists, bottom/top slabs, boxes and spheres.
#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace iarap {

enum class RegionKind {
  Indices, // the listed vertex indices
  Bottom,  // coordinate along axis <= min + fraction * extent (extent of the bounding box along axis)
  Top,     // coordinate along axis >= max - fraction * extent
  Box,     // lo <= position <= hi componentwise
  Sphere   // |position - center| <= radius
};

struct Region {
  RegionKind kind = RegionKind::Indices;
  std::vector<int> indices; // Indices
  int axis = 1;             // Bottom, Top: 0 = x, 1 = y, 2 = z
  double fraction = 0.1;    // Bottom, Top: share of the bounding-box extent, in (0, 1]
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero(); // Box corners
  Eigen::Vector3d center = Eigen::Vector3d::Zero();                           // Sphere
  double radius = 0;                                                          // Sphere
  // Box, Sphere: when true, points are in bounding-box coordinates ((0,0,0) = min corner,
  // (1,1,1) = max corner per axis) and the radius is a fraction of the bounding-box diagonal.
  bool relative = false;
  std::string path = "region"; // where the rule came from (a JSON path), named in error messages
};

// Axis-aligned bounding box of the finite rows of V (#V x 3); rows with NaN/Inf are ignored.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
  double diagonal() const { return (max - min).stableNorm(); } // no overflow of squares at 1e200
};
BoundingBox bounding_box(const Eigen::MatrixXd& V);

// Sorted, distinct indices of the vertices of V (#V x 3) the region selects, in a bounding box
// computed by bounding_box(V). Throws InputError naming region.path when an index is out of range
// (giving the mesh size) and when the region selects no vertex.
std::vector<int> select_region(const Region& region, const Eigen::MatrixXd& V, const BoundingBox& box);

} // namespace iarap
