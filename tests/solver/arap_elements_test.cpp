#include "iarap/solver/arap_elements.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/cotan.h"
#include "solver_fixtures.h"

#include <gtest/gtest.h>

namespace {

using namespace iarap;

double relative_difference(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  return (A - B).norm() / B.norm();
}

void expect_consistent(const ArapElements& el, const Eigen::MatrixXd& V) {
  ASSERT_EQ(el.cell_start.size(), static_cast<size_t>(el.size()) + 1);
  for (Eigen::Index e = 0; e < el.size(); ++e) {
    EXPECT_NEAR(el.b_value.row(e).sum(), 0.0, 1e-12) << "element " << e; // b encodes a vector
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k)
      s += el.b_value(e, k) * V.row(el.b_index(e, k));
    EXPECT_LT((s - el.s_hat.row(e)).norm(), 1e-15 * test::bbox_diagonal(V));
  }
  // The transposed incidences list every (element, cell) and (element, slot) pair once.
  EXPECT_EQ(el.cell_element.size(), el.cell.size());
  size_t nonzeros = 0;
  for (Eigen::Index e = 0; e < el.size(); ++e)
    for (int k = 0; k < 3; ++k)
      nonzeros += el.b_value(e, k) != 0.0;
  EXPECT_EQ(el.vertex_slot.size(), nonzeros);
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
    if (seg.b_value.row(s).cwiseAbs().maxCoeff() == 0.0)
      continue;
    largest = std::max(largest, (seg.s_hat.row(s) - el.s_hat.row(e++)).norm());
  }
  EXPECT_LT(largest, 1e-14 * test::bbox_diagonal(m.V));
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

} // namespace
