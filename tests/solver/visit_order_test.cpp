// The iterations' visit order (ArapElements::visit_order): a permutation with the vertex cells first, one
// that keeps mesh neighbours close where the file does not, and invisible to the caller: the solve of a mesh
// and of the same mesh with its vertices shuffled agree, row by row in each file's order.
#include "iarap/core/threads.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/solver/arap.h"
#include "solver_fixtures.h"

#include "solver/streamed_layout.h" // the layout the iterations stream
#include "solver/visit_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace iarap {
namespace {

using test::SolverMesh;

ArapOptions visit_options_for(ArapMethod method) {
  ArapOptions options;
  options.method = method;
  options.intrinsic.refine_boundary = true; // the bunny has holes: inserted boundary cells after the vertices
  options.keep_elements = true;             // compared with the element arrays
  return options;
}

// Mean |position(i) - position(j)| over the directed edges of F, position[v] = where v sits in an order.
double mean_edge_span(const Eigen::MatrixXi& F, const std::vector<int>& position) {
  double sum = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      sum +=
          std::abs(position[static_cast<size_t>(F(f, k))] - position[static_cast<size_t>(F(f, (k + 1) % 3))]);
  return sum / (3.0 * static_cast<double>(F.rows()));
}

// The mesh with its vertices renumbered: vertex v becomes new_index[v].
SolverMesh renumbered(const SolverMesh& m, const std::vector<int>& new_index) {
  SolverMesh out{Eigen::MatrixXd(m.V.rows(), 3), Eigen::MatrixXi(m.F.rows(), 3)};
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) out.V.row(new_index[static_cast<size_t>(v)]) = m.V.row(v);
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f, k) = new_index[static_cast<size_t>(m.F(f, k))];
  return out;
}

std::vector<int> shuffled_indices(int n, unsigned seed) {
  std::vector<int> index(static_cast<size_t>(n));
  std::iota(index.begin(), index.end(), 0);
  std::shuffle(index.begin(), index.end(), std::mt19937(seed));
  return index;
}

class VisitOrder : public test::SingleThreadTest {}; // the bunny, ~3500 vertices

// The in-place permutations (a solve's rotations) equal the copying ones, element for element, on a random
// permutation (cycles of every length) and on the identity and a single swap.
TEST(VisitOrderPermutation, InPlaceEqualsTheCopy) {
  const int n = 1000;
  std::vector<std::vector<int>> orders = {shuffled_indices(n, 7), shuffled_indices(n, 0), {}};
  std::sort(orders[1].begin(), orders[1].end()); // the identity
  orders[2] = orders[1];
  std::swap(orders[2][3], orders[2][900]);
  std::vector<double> values(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) values[static_cast<size_t>(i)] = 0.5 * i * i - 3.0;
  for (const std::vector<int>& order : orders) {
    std::vector<double> copy, in_place = values;
    detail::to_visit_order(order, values, copy);
    detail::to_visit_order_in_place(order, in_place);
    EXPECT_EQ(in_place, copy);
    detail::from_visit_order(order, values, copy);
    in_place = values;
    detail::from_visit_order_in_place(order, in_place);
    EXPECT_EQ(in_place, copy);
  }
}

TEST_F(VisitOrder, PermutesTheCellsWithTheVerticesFirst) {
  const SolverMesh m = test::bunny();
  const Eigen::VectorXi fixed = test::to_vector(test::axis_band(m.V, 1, 0.1, -1));
  for (ArapMethod method : test::kAllMethods) {
    const ArapData data = arap_precompute(m.V, m.F, fixed, visit_options_for(method));
    const ArapElements& el = data.elements;
    const detail::StreamedLayout& sl = detail::streamed(el);
    const int n = el.num_vertices;
    ASSERT_EQ(sl.visit_order.size(), static_cast<size_t>(el.num_cells));
    std::vector<int> sorted = sl.visit_order;
    std::sort(sorted.begin(), sorted.end());
    for (int c = 0; c < el.num_cells; ++c)
      ASSERT_EQ(sorted[static_cast<size_t>(c)], c) << arap_method_name(method);
    EXPECT_LT(*std::max_element(sl.visit_order.begin(), sl.visit_order.begin() + n), n);
    for (int p = n; p < el.num_cells; ++p) EXPECT_EQ(sl.visit_order[static_cast<size_t>(p)], p);
    // Each position streams exactly the elements of its cell.
    for (int p = 0; p < el.num_cells; ++p) {
      const auto c = static_cast<size_t>(sl.visit_order[static_cast<size_t>(p)]);
      ASSERT_EQ(sl.cell_entry_start[static_cast<size_t>(p) + 1] - sl.cell_entry_start[static_cast<size_t>(p)],
                el.cell_element_start[c + 1] - el.cell_element_start[c]);
    }
  }
}

// What the order is for: neighbours close together. A 1-to-4 subdivision numbers each edge's midpoint after
// all the corners, and a shuffle scatters everything; the breadth-first order keeps an edge's ends within
// about one front (~sqrt(#V) positions) of each other. Measured on the bunny (mean over edges): 135 against
// the file's 3768 subdivided (13.9K vertices), 65 against 1167 shuffled (3.5K); a factor of 10 leaves
// room for a different start or tie-break.
TEST_F(VisitOrder, KeepsNeighboursCloseWhereTheFileDoesNot) {
  SolverMesh subdivided = test::bunny();
  subdivide_midpoint(subdivided.V, subdivided.F, 1);
  const SolverMesh shuffled =
      renumbered(test::bunny(), shuffled_indices(static_cast<int>(test::bunny().V.rows()), 5));
  for (const SolverMesh* m : {static_cast<const SolverMesh*>(&subdivided), &shuffled}) {
    const Eigen::VectorXi fixed = test::to_vector(test::axis_band(m->V, 1, 0.1, -1));
    const ArapData data = arap_precompute(m->V, m->F, fixed, visit_options_for(ArapMethod::Arap));
    const int n = static_cast<int>(m->V.rows());
    std::vector<int> file(static_cast<size_t>(n)), visit(static_cast<size_t>(n));
    std::iota(file.begin(), file.end(), 0);
    for (int p = 0; p < n; ++p)
      visit[static_cast<size_t>(detail::streamed(data.elements).visit_order[static_cast<size_t>(p)])] = p;
    const double file_span = mean_edge_span(m->F, file), visit_span = mean_edge_span(m->F, visit);
    EXPECT_LT(visit_span * 10.0, file_span) << "file " << file_span << ", visit " << visit_span;
  }
}

// The order is internal: the same mesh with shuffled vertices gives the same solve, each in its file's order.
// The two runs differ only in rounding (CHOLMOD's fill-reducing order of the shuffled matrix differs, so the
// factor's sums run in another order): ~1e-15 relative per step, and the plain iteration is a contraction,
// so 1e-10 of the bounding-box diagonal after 20 iterations is a wide margin (measured: 2.4e-14). Rotations
// of the vertex cells to 1e-8 (measured: 7e-12): polar decompositions of covariances equal to rounding.
TEST_F(VisitOrder, SolveDoesNotDependOnTheFileVertexOrder) {
  const SolverMesh m = test::bunny();
  const std::vector<int> new_index = shuffled_indices(static_cast<int>(m.V.rows()), 11);
  const SolverMesh s = renumbered(m, new_index);
  const std::vector<int> bottom = test::axis_band(m.V, 1, 0.1, -1), top = test::axis_band(m.V, 1, 0.1, 1);
  std::vector<int> fixed_m = bottom;
  fixed_m.insert(fixed_m.end(), top.begin(), top.end());
  std::vector<int> fixed_s;
  for (const int v : fixed_m) fixed_s.push_back(new_index[static_cast<size_t>(v)]);
  Eigen::MatrixXd targets = test::rows_of(m.V, test::to_vector(fixed_m));
  targets.bottomRows(static_cast<Eigen::Index>(top.size())).rowwise() +=
      Eigen::RowVector3d(0.2, 0.05, 0.0) * test::bbox_diagonal(m.V);
  ArapSolveOptions solve;
  solve.max_iterations = 20;
  solve.tolerance = -1;
  solve.accelerator = ArapAccelerator::None;
  const double diagonal = test::bbox_diagonal(m.V);
  for (ArapMethod method : test::kAllMethods) {
    ArapData data_m = arap_precompute(m.V, m.F, test::to_vector(fixed_m), visit_options_for(method));
    ArapData data_s = arap_precompute(s.V, s.F, test::to_vector(fixed_s), visit_options_for(method));
    Eigen::MatrixXd U_m = m.V, U_s = s.V;
    const ArapReport report_m = arap_solve(data_m, targets, U_m, solve);
    const ArapReport report_s = arap_solve(data_s, targets, U_s, solve);
    const std::string name = arap_method_name(method);
    EXPECT_NEAR(report_s.energies.back(), report_m.energies.back(),
                1e-12 * std::abs(report_m.energies.back()))
        << name;
    double distance = 0.0, rotation = 0.0;
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
      const auto w = static_cast<size_t>(new_index[static_cast<size_t>(v)]);
      distance = std::max(distance, (U_s.row(static_cast<Eigen::Index>(w)) - U_m.row(v)).norm());
      rotation = std::max(
          rotation, (arap_rotations(data_s)[w] - arap_rotations(data_m)[static_cast<size_t>(v)]).norm());
    }
    EXPECT_LT(distance, 1e-10 * diagonal) << name;
    EXPECT_LT(rotation, 1e-8) << name;
  }
}

} // namespace
} // namespace iarap
