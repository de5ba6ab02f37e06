// Packing flattened charts into the unit square (uv_atlas.h).
#pragma once
#include <Eigen/Core>
#include <vector>

namespace iarap::param_detail {

// Where a chart goes: uv_atlas = scale * rotation * uv + translation (rotation a proper rotation, scale
// shared by all charts so that they keep their relative sizes).
struct ChartPlacement {
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
};

struct ChartPacking {
  double scale = 0;
  std::vector<ChartPlacement> placements;
};

// Each chart (its UV rows, #v x 2, and triangles, #f x 3, at least one) is first turned to its
// minimum-area bounding rectangle (an edge of the convex hull lies on it: Freeman and Shapira 1975), lying
// flat. Two packings, the better (larger scale) kept:
// - shelves: the rectangles first-fit decreasing by height (Coffman, Garey, Johnson and Tarjan 1980) at
//   the largest scale that fits (bisection), gap texels apart and gap / 2 from the border;
// - a raster (as xatlas packs): the charts, largest first, each turned by 0, 90, 180 or 270 degrees (the
//   turn whose top ends lowest), put at the lowest free place of a bitmap of min(texture_size, 512)^2
//   cells, a chart's cells those its triangles' bounding boxes touch (so it covers all of the chart),
//   dilated by the gap rounded up to whole cells for the test against the charts placed before; the scale
//   raised from the shelves' in steps of 3% while every chart finds a place, then three bisection steps.
// Charts are then at least gap texels apart and inside the unit square. Throws InputError when even at a
// vanishing scale the gaps do not fit (too many charts for the texture and padding).
ChartPacking pack_charts(const std::vector<Eigen::MatrixXd>& chart_uv,
                         const std::vector<Eigen::MatrixXi>& chart_faces, int texture_size, double gap);

} // namespace iarap::param_detail
