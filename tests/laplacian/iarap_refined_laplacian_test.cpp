// The Laplacian of the boundary-robust iARAP (issue 8): B^T D_w B over the refined triangulation's segments.
#include "iarap/intrinsic/intrinsic_delaunay.h"
#include "iarap/laplacian/laplacians.h"
#include "iarap/mesh/edge_topology.h"
#include "intrinsic/mesh_generators.h"

#include <gtest/gtest.h>

using namespace iarap;

TEST(IarapRefinedLaplacian, SymmetricConstantsInKernelAndLinearlyPreciseOnFlatBoundaryMeshes) {
  // A flat strip whose rows are sheared by half a cell (obtuse boundary triangles), made non-Delaunay by
  // random flips, so refinement inserts boundary points.
  iarap::test::TestMesh m = iarap::test::sheared_strip(12, 4);
  iarap::test::random_planar_flips(m, 40, 9);
  IntrinsicOptions options;
  options.refine_boundary = true;
  const IntrinsicDelaunay refined = intrinsic_delaunay(m.V, m.F, options);
  const Eigen::SparseMatrix<double> L = laplacian(m.V, m.F, LaplacianKind::IarapRefined);
  const double scale = Eigen::VectorXd(L.diagonal()).cwiseAbs().maxCoeff();
  EXPECT_LE((Eigen::SparseMatrix<double>(L.transpose()) - L).norm(), 1e-12 * scale);
  EXPECT_LE((L * Eigen::VectorXd::Ones(L.cols())).cwiseAbs().maxCoeff(), 1e-12 * scale);
  // Interior vertices reproduce linear functions (the boundary rows see the outside, as for every Laplacian).
  std::vector<char> boundary(static_cast<size_t>(m.V.rows()), 0);
  const EdgeTopology topo = edge_topology(m.F, static_cast<int>(m.V.rows()));
  for (int e = 0; e < topo.E.rows(); ++e)
    if (topo.face_count(e) == 1)
      boundary[static_cast<size_t>(topo.E(e, 0))] = boundary[static_cast<size_t>(topo.E(e, 1))] = 1;
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::VectorXd Lx = L * m.V.col(axis);
    for (int v = 0; v < m.V.rows(); ++v)
      if (!boundary[static_cast<size_t>(v)]) {
        EXPECT_NEAR(Lx(v), 0.0, 1e-10 * scale) << "vertex " << v;
      }
  }
  // Same sparsity as the input mesh: inserted points are no unknowns.
  EXPECT_EQ(L.rows(), m.V.rows());
  EXPECT_GT(refined.triangulation.inserted_t.size(), 0);
  EXPECT_EQ(parse_laplacian_kind("iarap-refined"), LaplacianKind::IarapRefined);
}
