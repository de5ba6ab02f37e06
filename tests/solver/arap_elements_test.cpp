#include "iarap/solver/arap_elements.h"

#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/cotan.h"
#include "intrinsic/mesh_generators.h"
#include "solver_fixtures.h"

// Internal: arap_precompute's path from the traces to the elements, checked against the public one.
#include "intrinsic/intrinsic_phases.h"
#include "intrinsic/segments.h"
#include "solver/traced_elements.h"

#include "solver/streamed_layout.h" // the layout the iterations stream

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace iarap;

double relative_difference(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  return (A - B).norm() / B.norm();
}

void expect_consistent(const ArapElements& el, const Eigen::MatrixXd& V) {
  const detail::StreamedLayout& sl = detail::streamed(el);
  ASSERT_EQ(el.cell_start.size(), static_cast<size_t>(el.size()) + 1);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    EXPECT_NEAR(el.b_value.row(e).sum(), 0.0, 1e-12) << "element " << e; // b encodes a vector
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) s += el.b_value(e, k) * V.row(el.b_index(e, k));
    EXPECT_LT((s - el.s_hat.row(e)).norm(), 1e-15 * test::bbox_diagonal(V));
  }
  // The transposed incidence lists every (element, cell) pair once.
  EXPECT_EQ(el.cell_element.size(), el.cell.size());
  // The regrouped right-hand side: per vertex one term per distinct cell, in increasing cell position, and
  // together they hold what the vertex's non-zeros give straight from the elements, sum_e |cells(e)| w_e
  // (b_e)_v s_hat_e. Only the order of the additions differs: a few ulps of the sum of magnitudes.
  ASSERT_EQ(sl.rhs_term_start.size(), static_cast<size_t>(el.num_vertices) + 1);
  std::vector<int> position(sl.visit_order.size());
  for (size_t p = 0; p < position.size(); ++p)
    position[static_cast<size_t>(sl.visit_order[p])] = static_cast<int>(p);
  Eigen::MatrixX3d direct = Eigen::MatrixX3d::Zero(el.num_vertices, 3), magnitude = direct,
                   regrouped = direct;
  for (Eigen::Index e = 0; e < el.size(); ++e)
    for (int k = 0; k < 3; ++k) {
      if (el.b_value(e, k) == 0.0) continue;
      const Eigen::RowVector3d q =
          (el.cell_start[e + 1] - el.cell_start[e]) * el.w(e) * el.b_value(e, k) * el.s_hat.row(e);
      direct.row(position[static_cast<size_t>(el.b_index(e, k))]) += q;
      magnitude.row(position[static_cast<size_t>(el.b_index(e, k))]) += q.cwiseAbs();
    }
  for (int v = 0; v < el.num_vertices; ++v)
    for (int t = sl.rhs_term_start[static_cast<size_t>(v)]; t < sl.rhs_term_start[static_cast<size_t>(v) + 1];
         ++t) {
      const detail::RhsTerm& term = sl.rhs_term[static_cast<size_t>(t)];
      if (t > sl.rhs_term_start[static_cast<size_t>(v)]) {
        EXPECT_LT(sl.rhs_term[static_cast<size_t>(t) - 1].cell, term.cell) << "vertex at position " << v;
      }
      const double p0 = term.p[0], p1 = term.p[1], p2 = term.p[2]; // packed fields: copies, no const&
      regrouped.row(v) += Eigen::RowVector3d(p0, p1, p2);
    }
  EXPECT_TRUE(((direct - regrouped).cwiseAbs().array() <= 1e-14 * magnitude.array()).all())
      << "largest difference " << (direct - regrouped).cwiseAbs().maxCoeff();
}

// The element sum reproduces the cotan Laplacian: 2 x for original ARAP (each edge in 2 cells),
// 3 x for spokes-and-rims (each face edge in the face's 3 cells). Relative 1e-13: only summation order
// differs.
TEST(ArapElements, EdgeElementsGiveTwiceTheCotanLaplacian) {
  const auto m = test::bunny();
  const ArapElements el = arap_edge_elements(m.V, m.F);
  expect_consistent(el, m.V);
  EXPECT_LT(relative_difference(element_system_matrix(el), 2.0 * cotan_laplacian(m.V, m.F)), 1e-13);
  EXPECT_LT(el.w.minCoeff(), 0.0) << "bunny has non-Delaunay edges; their negative weights must be kept";
}

TEST(ArapElements, SpokesRimsElementsGiveThreeTimesTheCotanLaplacian) {
  const auto m = test::bunny();
  const ArapElements el = spokes_rims_elements(m.V, m.F);
  expect_consistent(el, m.V);
  EXPECT_EQ(el.size(), 3 * m.F.rows());
  EXPECT_LT(relative_difference(element_system_matrix(el), 3.0 * cotan_laplacian(m.V, m.F)), 1e-13);
}

TEST(ArapElements, IarapElementsGiveTwiceBtDwB) {
  const auto m = test::bunny();
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  const ArapElements el = iarap_elements(m.V, idt);
  expect_consistent(el, m.V);
  const Segments& seg = idt.segments;
  const Eigen::SparseMatrix<double> BtDB = seg.B.transpose() * seg.weight.asDiagonal() * seg.B; // Eq. 17
  EXPECT_LT(relative_difference(element_system_matrix(el), 2.0 * BtDB), 1e-13);
  // Recomputed rest vectors agree with the segments' own (they differ only in summation order).
  double largest = 0.0;
  for (Eigen::Index s = 0, e = 0; s < seg.edge.size(); ++s) {
    if (seg.b_value.row(s).cwiseAbs().maxCoeff() == 0.0) continue;
    largest = std::max(largest, (seg.s_hat.row(s) - el.s_hat.row(e++)).norm());
  }
  EXPECT_LT(largest, 1e-14 * test::bbox_diagonal(m.V));
}

// The streamed layout, the right-hand side's terms included (a counting sort over per-thread ranges of
// cells), is the same bit for bit whatever the number of threads: 3 splits the cells into ranges whose
// shares of a vertex's run must land after those of the ranges before them.
TEST(ArapElements, StreamedLayoutDoesNotDependOnTheThreadCount) {
  const auto m = test::bunny();
  const IntrinsicDelaunay idt = intrinsic_delaunay(m.V, m.F);
  auto build = [&](int which) {
    return which == 0   ? arap_edge_elements(m.V, m.F)
           : which == 1 ? spokes_rims_elements(m.V, m.F)
                        : iarap_elements(m.V, idt);
  };
  for (int which = 0; which < 3; ++which) {
    set_thread_count(1);
    const ArapElements one = build(which);
    for (const int threads : {2, 3}) {
      set_thread_count(threads);
      const ArapElements many = build(which);
      const detail::StreamedLayout &a = detail::streamed(many), &b = detail::streamed(one);
      EXPECT_EQ(a.visit_order, b.visit_order) << which << ", " << threads << " threads";
      EXPECT_EQ(a.cell_entry_start, b.cell_entry_start) << which << ", " << threads << " threads";
      ASSERT_EQ(a.rhs_term_start, b.rhs_term_start) << which << ", " << threads << " threads";
      bool same = true;
      for (size_t t = 0; t < b.rhs_term.size(); ++t) {
        same = same && a.rhs_term[t].cell == b.rhs_term[t].cell;
        for (int d = 0; d < 3; ++d) same = same && a.rhs_term[t].p[d] == b.rhs_term[t].p[d];
      }
      EXPECT_TRUE(same) << which << ", " << threads << " threads";
    }
  }
  set_thread_count(0);
}

TEST(ArapElements, DegenerateFaceAndBadIndicesAreNamed) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 1; // face 1 has three collinear corners: zero area
  try {
    arap_edge_elements(V, F);
    FAIL() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("face 1 is degenerate"), std::string::npos) << e.what();
  }
  auto bad = test::bumpy_patch(3);
  bad.F(2, 1) = 99;
  try {
    spokes_rims_elements(bad.V, bad.F);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 2 uses vertex 99"), std::string::npos) << e.what();
  }
}

void expect_same_elements(const ArapElements& a, const ArapElements& b, const std::string& name) {
  EXPECT_EQ(a.num_vertices, b.num_vertices) << name;
  EXPECT_EQ(a.num_cells, b.num_cells) << name;
  EXPECT_EQ(a.b_index, b.b_index) << name;
  EXPECT_EQ(a.b_value, b.b_value) << name;
  EXPECT_EQ(a.s_hat, b.s_hat) << name;
  EXPECT_EQ(a.w, b.w) << name;
  EXPECT_EQ(a.face, b.face) << name;
  EXPECT_EQ(a.cell_start, b.cell_start) << name;
  EXPECT_EQ(a.cell, b.cell) << name;
  EXPECT_EQ(a.cell_element_start, b.cell_element_start) << name;
  EXPECT_EQ(a.cell_element, b.cell_element) << name;
  const detail::StreamedLayout &sa = detail::streamed(a), &sb = detail::streamed(b);
  EXPECT_EQ(sa.rhs_term_start, sb.rhs_term_start) << name;
  for (size_t t = 0; t < std::min(sa.rhs_term.size(), sb.rhs_term.size()); ++t) {
    EXPECT_EQ(sa.rhs_term[t].cell, sb.rhs_term[t].cell) << name << " term " << t;
    for (int d = 0; d < 3; ++d) { // packed fields: compared as copies (EXPECT_EQ takes const&)
      const double pa = sa.rhs_term[t].p[d], pb = sb.rhs_term[t].p[d];
      EXPECT_EQ(pa, pb) << name << " term " << t;
    }
  }
}

// arap_precompute builds iARAP's elements from the traces without the Segments, and its signpost
// triangulation from the topology, face cotangents and corner angles it computed once for the cotan
// Laplacian too (signpost_input): they must equal, bit for bit, what iarap_elements makes of
// intrinsic_delaunay's segments, on a non-Delaunay closed mesh, a curved patch with boundary and a strip
// whose boundary refinement inserts points (extra cells). The shared cotangents are face_cotangents', bit
// for bit, since L is assembled from them (same lengths, same arithmetic).
TEST(ArapElements, TracedElementsEqualSegmentElements) {
  const auto bunny = test::bunny();
  const auto patch = test::bumpy_patch(12);
  const test::TestMesh strip = test::sheared_strip(16, 4, 2.0);
  const std::pair<const char*, std::pair<Eigen::MatrixXd, Eigen::MatrixXi>> cases[] = {
      {"bunny", {bunny.V, bunny.F}}, {"bumpy patch", {patch.V, patch.F}}, {"bent strip", {strip.V, strip.F}}};
  for (const auto& [name, mesh] : cases) {
    IntrinsicOptions options;
    options.refine_boundary = name == std::string("bent strip");
    detail::SignpostInput input = detail::signpost_input(mesh.first, mesh.second, options.refine_boundary);
    EXPECT_EQ(*input.C, face_cotangents(mesh.first, mesh.second)) << name;
    const detail::TracedTriangulation traced =
        detail::trace_phase(detail::flip_phase(mesh.first, mesh.second, options, &input), false);
    EXPECT_FALSE(input.topology || input.C) << name << ": the build drops its references";
    ArapElements fused = detail::traced_iarap_elements(mesh.first, traced.triangulation, traced.traces);
    detail::finish_elements(mesh.first, fused, true);
    const ArapElements reference =
        iarap_elements(mesh.first, intrinsic_delaunay(mesh.first, mesh.second, options));
    EXPECT_GT(traced.traces.points.size(), 0u) << name << ": some edges must be traced";
    if (options.refine_boundary) {
      EXPECT_GT(fused.num_cells, fused.num_vertices) << name;
    }
    EXPECT_EQ(fused.size(), traced.traces.segment_count()) << name;
    expect_same_elements(fused, reference, name);
  }
}

// A segment with b = 0 (two equal trace points) adds nothing and is left out by both builders alike.
TEST(ArapElements, ZeroLengthSegmentsAreLeftOut) {
  const auto m = test::bunny();
  detail::TracedTriangulation traced = detail::trace_phase(detail::flip_phase(m.V, m.F, {}));
  detail::CompactTraces& traces = traced.traces;
  ASSERT_GT(traces.start.size(), 2u);
  // Repeat the second point of the first flipped edge.
  traces.points.insert(traces.points.begin() + 1, traces.points[1]);
  for (size_t k = 1; k < traces.start.size(); ++k) ++traces.start[k];
  ArapElements fused = detail::traced_iarap_elements(m.V, traced.triangulation, traces);
  detail::finish_elements(m.V, fused, true);
  IntrinsicDelaunay idt;
  idt.triangulation = traced.triangulation;
  idt.segments = detail::build_segments(m.V, traced.triangulation, traces, false);
  EXPECT_EQ(idt.segments.b_value.rowwise().squaredNorm().minCoeff(), 0.0) << "the repeated point makes b = 0";
  EXPECT_EQ(fused.size(), traces.segment_count() - 1);
  expect_same_elements(fused, iarap_elements(m.V, idt), "bunny with a repeated trace point");
}

} // namespace
