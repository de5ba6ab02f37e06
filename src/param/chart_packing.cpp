#include "chart_packing.h"

#include "packing_bitmap.h"

#include "iarap/core/errors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

namespace iarap::param_detail {

namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// Andrew's monotone chain: the convex hull counter-clockwise, collinear points dropped.
std::vector<Eigen::Vector2d> convex_hull(const Eigen::MatrixXd& uv) {
  std::vector<Eigen::Vector2d> p(static_cast<std::size_t>(uv.rows()));
  for (Eigen::Index i = 0; i < uv.rows(); ++i) p[static_cast<std::size_t>(i)] = uv.row(i).transpose();
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

struct Rectangle {
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  Eigen::Vector2d min = Eigen::Vector2d::Zero(); // lower corner of the rotated chart's bounding box
  double width = 0, height = 0;                  // width >= height
};

// The minimum-area bounding rectangle has a side on an edge of the hull; turned to lie flat.
Rectangle flat_min_area_rectangle(const Eigen::MatrixXd& uv) {
  const std::vector<Eigen::Vector2d> hull = convex_hull(uv);
  Rectangle best;
  double best_area = -1;
  const std::size_t edges = hull.size() < 3 ? 1 : hull.size();
  for (std::size_t i = 0; i < edges; ++i) {
    Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
    if (hull.size() >= 2) {
      const Eigen::Vector2d d = (hull[(i + 1) % hull.size()] - hull[i]).normalized();
      rotation << d.x(), d.y(), -d.y(), d.x(); // takes d to the u axis
    }
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = -lo;
    for (const Eigen::Vector2d& q : hull) {
      lo = lo.cwiseMin(rotation * q);
      hi = hi.cwiseMax(rotation * q);
    }
    const double area = (hi - lo).prod();
    if (best_area < 0 || area < best_area) {
      best_area = area;
      best.rotation = rotation;
      best.min = lo;
      best.width = hi.x() - lo.x();
      best.height = hi.y() - lo.y();
    }
  }
  if (best.height > best.width) { // a quarter turn, (x, y) -> (-y, x)
    Eigen::Matrix2d quarter;
    quarter << 0, -1, 1, 0;
    best.rotation = quarter * best.rotation;
    best.min = Eigen::Vector2d(-(best.min.y() + best.height), best.min.x());
    std::swap(best.width, best.height);
  }
  return best;
}

// First fit decreasing height: boxes (in order of decreasing height) on shelves across the square. Fills
// corner with each box's lower-left corner; false when they do not fit.
bool shelves_fit(const std::vector<Rectangle>& rects, const std::vector<std::size_t>& order, double scale,
                 double gap, std::vector<Eigen::Vector2d>& corner) {
  struct Shelf {
    double y, height, used;
  };
  std::vector<Shelf> shelves;
  double top = 0;
  for (std::size_t i : order) {
    const double w = scale * rects[i].width + gap, h = scale * rects[i].height + gap;
    if (w > 1) return false;
    auto shelf = std::find_if(shelves.begin(), shelves.end(),
                              [w, h](const Shelf& s) { return s.used + w <= 1 && h <= s.height; });
    if (shelf == shelves.end()) {
      if (top + h > 1) return false;
      shelves.push_back({top, h, 0});
      top += h;
      shelf = shelves.end() - 1;
    }
    corner[i] = Eigen::Vector2d(shelf->used, shelf->y);
    shelf->used += w;
  }
  return true;
}

CellMask runs_of(const std::vector<char>& cells, int width, int height) {
  CellMask mask;
  mask.width = width;
  mask.height = height;
  mask.runs.resize(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width;) {
      if (!cells[static_cast<std::size_t>(y * width + x)]) {
        ++x;
        continue;
      }
      const int begin = x;
      while (x < width && cells[static_cast<std::size_t>(y * width + x)]) ++x;
      mask.runs[static_cast<std::size_t>(y)].push_back({begin, x});
    }
  return mask;
}

// A chart at one scale and turn: its points in cells, offset so that the dilated mask starts at (0, 0).
struct RasterChart {
  Eigen::Matrix2d rotation;
  Eigen::Vector2d offset; // cells: position of a point p = scale_cells * rotation * uv + offset
  CellMask cells, dilated;
};

RasterChart raster_chart(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& faces,
                         const Eigen::Matrix2d& rotation, double scale_cells, int dilation) {
  RasterChart chart;
  chart.rotation = rotation;
  const Eigen::MatrixXd p = (scale_cells * (rotation * uv.transpose())).transpose();
  const Eigen::RowVector2d lo = p.colwise().minCoeff();
  chart.offset = (Eigen::Vector2d::Constant(dilation) - lo.transpose());
  const Eigen::RowVector2d extent = p.colwise().maxCoeff() - lo;
  const int width = static_cast<int>(std::floor(extent.x())) + 1 + 2 * dilation;
  const int height = static_cast<int>(std::floor(extent.y())) + 1 + 2 * dilation;
  std::vector<char> cells(static_cast<std::size_t>(width * height), 0);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    Eigen::Vector2d a = Eigen::Vector2d::Constant(INFINITY), b = -a;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d q = p.row(faces(f, k)).transpose() + chart.offset;
      a = a.cwiseMin(q);
      b = b.cwiseMax(q);
    }
    const int x1 = std::min(width - 1, static_cast<int>(b.x())),
              y1 = std::min(height - 1, static_cast<int>(b.y()));
    for (int y = std::max(0, static_cast<int>(a.y())); y <= y1; ++y)
      for (int x = std::max(0, static_cast<int>(a.x())); x <= x1; ++x)
        cells[static_cast<std::size_t>(y * width + x)] = 1;
  }
  chart.cells = runs_of(cells, width, height);
  // Dilation by `dilation` cells (a square): rows, then columns.
  std::vector<char> wide(cells.size(), 0), dilated(cells.size(), 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (cells[static_cast<std::size_t>(y * width + x)])
        for (int dx = std::max(0, x - dilation); dx <= std::min(width - 1, x + dilation); ++dx)
          wide[static_cast<std::size_t>(y * width + dx)] = 1;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (wide[static_cast<std::size_t>(y * width + x)])
        for (int dy = std::max(0, y - dilation); dy <= std::min(height - 1, y + dilation); ++dy)
          dilated[static_cast<std::size_t>(dy * width + x)] = 1;
  chart.dilated = runs_of(dilated, width, height);
  return chart;
}

// Places every chart (largest first) at the given scale: returns the rows the placed cells reach (their
// highest top), or -1 when a chart finds no place.
int raster_fit(const std::vector<Eigen::MatrixXd>& chart_uv, const std::vector<Eigen::MatrixXi>& chart_faces,
               const std::vector<Rectangle>& rects, const std::vector<std::size_t>& order, double scale,
               int dilation, CellBitmap& bitmap, std::vector<ChartPlacement>& placements) {
  bitmap.clear();
  const int cells = bitmap.size();
  int used_rows = 0;
  Eigen::Matrix2d quarter;
  quarter << 0, -1, 1, 0;
  for (std::size_t i : order) {
    RasterChart best;
    Eigen::Vector2i best_place(-1, -1);
    Eigen::Matrix2d rotation = rects[i].rotation;
    for (int turn = 0; turn < 4; ++turn, rotation = quarter * rotation) {
      RasterChart chart = raster_chart(chart_uv[i], chart_faces[i], rotation, scale * cells, dilation);
      const auto top = [](const Eigen::Vector2i& p, const RasterChart& c) {
        return p.y() + c.dilated.height;
      };
      // A turn can only win with its top at most the best one's (the same choice as an unbounded search).
      const Eigen::Vector2i place =
          lowest_place(bitmap, chart.dilated, best_place.x() < 0 ? cells : top(best_place, best));
      if (place.x() < 0) continue;
      if (best_place.x() < 0 || top(place, chart) < top(best_place, best) ||
          (top(place, chart) == top(best_place, best) && place.x() < best_place.x())) {
        best = std::move(chart);
        best_place = place;
      }
    }
    if (best_place.x() < 0) return -1;
    used_rows = std::max(used_rows, best_place.y() + best.cells.height);
    for (int y = 0; y < best.cells.height; ++y)
      for (const auto& [begin, end] : best.cells.runs[static_cast<std::size_t>(y)])
        bitmap.set(best_place.y() + y, best_place.x() + begin, best_place.x() + end);
    placements[i].rotation = best.rotation;
    placements[i].translation = (best.offset + best_place.cast<double>()) / cells;
  }
  return used_rows;
}

} // namespace

ChartPacking pack_charts(const std::vector<Eigen::MatrixXd>& chart_uv,
                         const std::vector<Eigen::MatrixXi>& chart_faces, int texture_size,
                         double gap_texels) {
  const double gap = gap_texels / texture_size;
  if (!(gap >= 0 && gap < 0.5))
    throw InputError("the padding (" + std::to_string(gap_texels) +
                     " texels) must be >= 0 and below half the "
                     "texture size (" +
                     std::to_string(texture_size) + ")");
  std::vector<Rectangle> rects;
  double area = 0, longest = 0;
  for (const Eigen::MatrixXd& uv : chart_uv) {
    rects.push_back(flat_min_area_rectangle(uv));
    area += rects.back().width * rects.back().height;
    longest = std::max(longest, rects.back().width);
  }
  std::vector<std::size_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&rects](std::size_t a, std::size_t b) { return rects[a].height > rects[b].height; });
  std::vector<Eigen::Vector2d> corner(rects.size()), best_corner;
  // The charts' rectangles cover at most the square: scale^2 area <= 1.
  double lo = 0, hi = std::min(1 / std::sqrt(area), (1 - gap) / longest);
  if (!shelves_fit(rects, order, lo, gap, corner))
    throw InputError(std::to_string(rects.size()) + " charts " + std::to_string(gap_texels) +
                     " texels apart do not fit a texture of " + std::to_string(texture_size) +
                     " texels: raise the texture size or lower the padding");
  best_corner = corner;
  if (shelves_fit(rects, order, hi, gap, corner)) {
    lo = hi;
    best_corner = corner;
  }
  for (int step = 0; step < 50 && hi - lo > 1e-12 * hi; ++step) {
    const double mid = (lo + hi) / 2;
    if (shelves_fit(rects, order, mid, gap, corner)) {
      lo = mid;
      best_corner = corner;
    } else {
      hi = mid;
    }
  }
  ChartPacking packing;
  packing.scale = lo;
  for (std::size_t i = 0; i < rects.size(); ++i) {
    ChartPlacement placement;
    placement.rotation = rects[i].rotation;
    placement.translation = best_corner[i] + Eigen::Vector2d::Constant(gap / 2) - lo * rects[i].min;
    packing.placements.push_back(placement);
  }
  // The raster, from 3% above the shelves' scale up while every chart finds a place: kept only above the
  // shelves' scale (else the shelves' placements stay). After a fit that used h of the n rows the next
  // scale is the last times 0.995 sqrt(n / h) (the rows the charts would fill at their density), none when
  // that is below 1% more; after a scale that did not fit, bisection to within 1%.
  const int cells = std::min(texture_size, 512);
  const int dilation = static_cast<int>(std::ceil(gap * cells - 1e-9));
  std::vector<std::size_t> by_area(order);
  std::stable_sort(by_area.begin(), by_area.end(), [&rects](std::size_t a, std::size_t b) {
    return rects[a].width * rects[a].height > rects[b].width * rects[b].height;
  });
  std::vector<ChartPlacement> trial(rects.size());
  CellBitmap bitmap(cells); // cleared by each trial
  const double limit = 1.5 / std::sqrt(area);
  double failed = 0; // the smallest scale seen not to fit (0: none yet)
  for (double scale = packing.scale * 1.03; scale < limit;) {
    const int used = raster_fit(chart_uv, chart_faces, rects, by_area, scale, dilation, bitmap, trial);
    if (used < 0) {
      failed = scale;
      break;
    }
    packing.scale = scale;
    packing.placements = trial;
    const double grow = 0.995 * std::sqrt(static_cast<double>(cells) / std::max(used, 1));
    if (grow < 1.01) break; // the rows left hold less than the bisection's 1%
    scale *= grow;
  }
  while (failed > 0 && failed > 1.01 * packing.scale) {
    const double scale = (packing.scale + failed) / 2;
    if (raster_fit(chart_uv, chart_faces, rects, by_area, scale, dilation, bitmap, trial) >= 0) {
      packing.scale = scale;
      packing.placements = trial;
    } else {
      failed = scale;
    }
  }
  return packing;
}

} // namespace iarap::param_detail
