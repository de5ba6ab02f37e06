#include "uv_overlap.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace iarap::param_detail {

namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return (d1 == 0 && on_segment(c, d, a)) || (d2 == 0 && on_segment(c, d, b)) ||
         (d3 == 0 && on_segment(a, b, c)) || (d4 == 0 && on_segment(a, b, d));
}

} // namespace

bool loop_crosses_itself(const Eigen::MatrixXd& UV, const std::vector<int>& loop) {
  const std::size_t n = loop.size();
  if (n < 4) return false; // a triangle's sides meet only at shared ends
  auto point = [&](std::size_t i) -> Eigen::Vector2d { return UV.row(loop[i % n]).transpose(); };
  Eigen::Vector2d lo = point(0), hi = point(0);
  for (std::size_t i = 1; i < n; ++i) {
    lo = lo.cwiseMin(point(i));
    hi = hi.cwiseMax(point(i));
  }
  const int cells = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(n))));
  const Eigen::Vector2d size = (hi - lo).cwiseMax(1e-300) / cells;
  auto cell_of = [&](double x, double lower, double step) {
    return std::clamp(static_cast<int>((x - lower) / step), 0, cells - 1);
  };
  std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(cells * cells));
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = point(i), b = point(i + 1);
    const int x0 = cell_of(std::min(a.x(), b.x()), lo.x(), size.x()),
              x1 = cell_of(std::max(a.x(), b.x()), lo.x(), size.x());
    const int y0 = cell_of(std::min(a.y(), b.y()), lo.y(), size.y()),
              y1 = cell_of(std::max(a.y(), b.y()), lo.y(), size.y());
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) grid[static_cast<std::size_t>(y * cells + x)].push_back(i);
  }
  for (const std::vector<std::size_t>& cell : grid)
    for (std::size_t p = 0; p < cell.size(); ++p)
      for (std::size_t q = p + 1; q < cell.size(); ++q) {
        const std::size_t i = cell[p], j = cell[q];
        if (j == i + 1 || (i == 0 && j == n - 1)) continue; // neighbours share an end
        if (segments_meet(point(i), point(i + 1), point(j), point(j + 1))) return true;
      }
  return false;
}

double rasterized_overlap(const Eigen::MatrixXd& corner_uv, const std::vector<bool>& use, int resolution) {
  std::vector<std::uint8_t> count(static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution),
                                  0);
  for (std::size_t f = 0; f < use.size(); ++f) {
    if (!use[f]) continue;
    Eigen::Vector2d p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = corner_uv.row(static_cast<Eigen::Index>(3 * f) + k).transpose() * resolution;
    const double area = orient(p[0], p[1], p[2]);
    if (area == 0) continue;
    const double sign = area > 0 ? 1 : -1;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}) - 0.5)));
    const int x1 =
        std::min(resolution - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}) - 0.5)));
    const int y1 =
        std::min(resolution - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d c(x + 0.5, y + 0.5);
        if (sign * orient(p[0], p[1], c) > 0 && sign * orient(p[1], p[2], c) > 0 &&
            sign * orient(p[2], p[0], c) > 0) {
          std::uint8_t& n = count[static_cast<std::size_t>(y) * static_cast<std::size_t>(resolution) +
                                  static_cast<std::size_t>(x)];
          if (n < 255) ++n;
        }
      }
  }
  std::size_t covered = 0, twice = 0;
  for (std::uint8_t n : count) {
    covered += n > 0;
    twice += n > 1;
  }
  return covered == 0 ? 0 : static_cast<double>(twice) / static_cast<double>(covered);
}

} // namespace iarap::param_detail
