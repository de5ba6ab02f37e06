#include "iarap/mesh/weld_representatives.h"

#include "disjoint_sets.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace iarap {

namespace {

using detail::DisjointSets;

// The predicate of every pair test. Zero tolerance is exact equality, handled by join_identical.
bool within(const Eigen::MatrixXd& V, int i, int j, double tolerance) {
  return (V.row(i) - V.row(j)).stableNorm() <= tolerance;
}

// Joins the copies of each position (a sort of the finite vertices by position, then index) and returns
// the first copy of each, the smallest index: a pile of 150K copies of one point leaves one vertex for
// the search by distance.
std::vector<int> join_identical(const Eigen::MatrixXd& V, DisjointSets& sets) {
  std::vector<int> order;
  order.reserve(static_cast<std::size_t>(V.rows()));
  for (int v = 0; v < static_cast<int>(V.rows()); ++v)
    if (V.row(v).allFinite()) order.push_back(v);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (V(a, k) != V(b, k)) return V(a, k) < V(b, k);
    return a < b;
  });
  std::vector<int> distinct;
  distinct.reserve(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i > 0 && V.row(order[i]) == V.row(order[i - 1]))
      sets.join(order[i - 1], order[i]);
    else
      distinct.push_back(order[i]);
  }
  return distinct;
}

struct Box {
  Eigen::Array3d lo, hi;
};

Box box_of(const Eigen::MatrixXd& V, const int* points, int n) {
  Box box{Eigen::Array3d::Constant(INFINITY), Eigen::Array3d::Constant(-INFINITY)};
  for (int i = 0; i < n; ++i) {
    box.lo = box.lo.min(V.row(points[i]).transpose().array());
    box.hi = box.hi.max(V.row(points[i]).transpose().array());
  }
  return box;
}

// Whether a point of a[0..na) lies within tolerance of a point of b[0..nb) (both reordered). Small sets
// pair up directly; else the larger set is halved at its median along its widest axis and halves whose
// box lies beyond the tolerance are skipped, so two large cells cost about (na + nb) log, not na nb.
bool any_pair_within(const Eigen::MatrixXd& V, int* a, int na, int* b, int nb, double tolerance) {
  if (static_cast<std::int64_t>(na) * nb <= 64) {
    for (int i = 0; i < na; ++i)
      for (int j = 0; j < nb; ++j)
        if (within(V, a[i], b[j], tolerance)) return true;
    return false;
  }
  Box box_a = box_of(V, a, na), box_b = box_of(V, b, nb);
  const Eigen::Array3d gap = (box_a.lo - box_b.hi).max(box_b.lo - box_a.hi).max(0.0);
  // The margin covers rounding: the box gap is a lower bound of every pair's distance.
  if (gap.matrix().stableNorm() > tolerance * (1 + 1e-9)) return false;
  if (na < nb) {
    std::swap(a, b);
    std::swap(na, nb);
    std::swap(box_a, box_b);
  }
  Eigen::Index axis = 0;
  (box_a.hi - box_a.lo).maxCoeff(&axis);
  const int half = na / 2;
  std::nth_element(a, a + half, a + na, [&](int p, int q) { return V(p, axis) < V(q, axis); });
  return any_pair_within(V, a, half, b, nb, tolerance) ||
         any_pair_within(V, a + half, na - half, b, nb, tolerance);
}

using CellKey = std::array<std::int64_t, 3>;

struct CellPoint {
  CellKey cell;
  int vertex;
  bool operator<(const CellPoint& o) const { return cell != o.cell ? cell < o.cell : vertex < o.vertex; }
};

// Cell side tolerance / 1.8 (below tolerance / sqrt 3): any two points of a cell are within the tolerance,
// so a cell joins as a whole whatever its size (one outlier at 1e30 puts a whole sheet into one cell), and
// points within the tolerance lie at most 2 cells apart per axis. Cell coordinates up to 2^44 keep the
// rounding of (x - lo) / cell below 1/256 of a cell; smaller tolerances take cells of extent / 2^44 and
// pair tests inside them.
constexpr double max_cell_coordinate = 17592186044416.0; // 2^44

struct Grid {
  double cell = 0.0;
  bool cells_join_whole = true;
  std::vector<CellPoint> points;  // sorted by cell, then vertex
  std::vector<std::size_t> start; // points of cell c: [start[c], start[c + 1])
};

Grid make_grid(const Eigen::MatrixXd& V, const std::vector<int>& distinct, double tolerance) {
  Eigen::Array3d lo = Eigen::Array3d::Constant(INFINITY), hi = Eigen::Array3d::Constant(-INFINITY);
  for (int v : distinct) {
    lo = lo.min(V.row(v).transpose().array());
    hi = hi.max(V.row(v).transpose().array());
  }
  const double extent = (hi - lo).maxCoeff(), finest = extent / max_cell_coordinate;
  Grid grid;
  grid.cell = tolerance / 1.8;
  grid.cells_join_whole = !(grid.cell < finest);
  if (!grid.cells_join_whole) grid.cell = finest;
  grid.points.reserve(distinct.size());
  for (int v : distinct) {
    CellPoint p{{0, 0, 0}, v};
    for (int k = 0; k < 3; ++k)
      p.cell[static_cast<std::size_t>(k)] =
          static_cast<std::int64_t>(std::floor((V(v, k) - lo(k)) / grid.cell));
    grid.points.push_back(p);
  }
  std::sort(grid.points.begin(), grid.points.end());
  for (std::size_t i = 0; i < grid.points.size(); ++i)
    if (i == 0 || grid.points[i].cell != grid.points[i - 1].cell) grid.start.push_back(i);
  grid.start.push_back(grid.points.size());
  return grid;
}

// Joins the points of one cell: all of them, or (tiny tolerances) each pair within the tolerance.
void join_cell(const Eigen::MatrixXd& V, const Grid& grid, std::size_t c, double tolerance,
               DisjointSets& sets) {
  const std::size_t c0 = grid.start[c], c1 = grid.start[c + 1];
  for (std::size_t i = c0 + 1; i < c1; ++i) {
    const int b = grid.points[i].vertex;
    if (grid.cells_join_whole) {
      sets.join(grid.points[c0].vertex, b);
      continue;
    }
    for (std::size_t j = c0; j < i; ++j) {
      const int a = grid.points[j].vertex;
      if (sets.find(a) != sets.find(b) && within(V, a, b, tolerance)) sets.join(a, b);
    }
  }
}

// Joins two different cells of the grid that hold a pair within the tolerance.
void join_cells(const Eigen::MatrixXd& V, const Grid& grid, std::size_t c, std::size_t d, double tolerance,
                DisjointSets& sets, std::vector<int>& scratch) {
  const std::size_t c0 = grid.start[c], c1 = grid.start[c + 1], d0 = grid.start[d], d1 = grid.start[d + 1];
  if (!grid.cells_join_whole) { // each pair
    for (std::size_t i = c0; i < c1; ++i)
      for (std::size_t j = d0; j < d1; ++j) {
        const int a = grid.points[i].vertex, b = grid.points[j].vertex;
        if (sets.find(a) != sets.find(b) && within(V, a, b, tolerance)) sets.join(a, b);
      }
    return;
  }
  const int a = grid.points[c0].vertex, b = grid.points[d0].vertex;
  if (sets.find(a) == sets.find(b)) return;
  scratch.clear();
  for (std::size_t i = c0; i < c1; ++i) scratch.push_back(grid.points[i].vertex);
  for (std::size_t j = d0; j < d1; ++j) scratch.push_back(grid.points[j].vertex);
  const int na = static_cast<int>(c1 - c0), nb = static_cast<int>(d1 - d0);
  if (any_pair_within(V, scratch.data(), na, scratch.data() + na, nb, tolerance)) sets.join(a, b);
}

// Joins the distinct positions within the tolerance: each cell with itself, then with the cells up to 2
// away that follow it in key order (each pair of cells once): 13 columns (x + dx, y + dy) of z ranges. The
// start of each column's range only grows from one cell to the next in key order, so one cursor per
// column walks the keys once: linear after the sort, where a binary search per column cost more than the
// old grid's 9.
void join_within_tolerance(const Eigen::MatrixXd& V, const std::vector<int>& distinct, double tolerance,
                           DisjointSets& sets) {
  const Grid grid = make_grid(V, distinct, tolerance);
  const std::size_t cells = grid.start.size() - 1;
  std::vector<CellKey> keys(cells);
  for (std::size_t c = 0; c < cells; ++c) keys[c] = grid.points[grid.start[c]].cell;
  std::array<std::size_t, 13> cursor{};
  std::vector<int> scratch;
  for (std::size_t c = 0; c < cells; ++c) {
    join_cell(V, grid, c, tolerance, sets);
    const CellKey& k = keys[c];
    std::size_t column = 0;
    for (std::int64_t dx = 0; dx <= 2; ++dx)
      for (std::int64_t dy = -2; dy <= 2; ++dy) {
        if (dx == 0 && dy < 0) continue;
        const std::int64_t z_from = dx == 0 && dy == 0 ? k[2] + 1 : k[2] - 2;
        const CellKey from{k[0] + dx, k[1] + dy, z_from}, to{k[0] + dx, k[1] + dy, k[2] + 2};
        std::size_t& d = cursor[column++];
        while (d < cells && keys[d] < from) ++d;
        for (std::size_t e = d; e < cells && keys[e] <= to; ++e)
          join_cells(V, grid, c, e, tolerance, sets, scratch);
      }
  }
}

} // namespace

Eigen::VectorXi weld_representatives(const Eigen::MatrixXd& V, double tolerance) {
  const int n = static_cast<int>(V.rows());
  Eigen::VectorXi representative(n);
  std::iota(representative.data(), representative.data() + n, 0);
  if (n == 0 || V.cols() != 3) return representative;
  DisjointSets sets(n);
  const std::vector<int> distinct = join_identical(V, sets);
  if (tolerance > 0 && distinct.size() > 1) join_within_tolerance(V, distinct, tolerance, sets);
  for (int v = 0; v < n; ++v) representative(v) = sets.find(v);
  return representative;
}

} // namespace iarap
