// The small systems of an atlas's charts (LSCM, UV global step): factorized by a simplicial LLT below
// SparseCholesky::set_simplicial_below instead of CHOLMOD's supernodal analysis, with the same solution
// to rounding; an indefinite one still falls back to LDL^T.
#include "iarap/mesh/cotan.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/lscm.h"
#include "iarap/solver/sparse_cholesky.h"
#include "param/disk_meshes.h"

#include "solver/constrained_solve.h"

#include <gtest/gtest.h>

namespace iarap {
namespace {

// The cotan Laplacian of a flat disk plus a small mass term (positive definite, like M_ff).
Eigen::SparseMatrix<double> disk_system(int rings, int sectors) {
  const test::TestMesh mesh = test::flat_disk(rings, sectors);
  Eigen::SparseMatrix<double> A = cotan_laplacian(mesh.V, mesh.F);
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1e-3;
  A.makeCompressed();
  return A;
}

TEST(ChartSolve, SimplicialBelowTheThresholdSolvesAsCholmodDoes) {
  const Eigen::SparseMatrix<double> A = disk_system(8, 24);
  ASSERT_LT(A.rows(), detail::simplicial_free_rows);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 2);

  SparseCholesky cholmod(A);
  ASSERT_EQ(cholmod.kind(), FactorizationKind::CholmodSupernodalLLT);
  SparseCholesky simplicial;
  simplicial.set_simplicial_below(detail::simplicial_free_rows);
  simplicial.factorize(A);
  EXPECT_EQ(simplicial.kind(), FactorizationKind::SimplicialLLT);
  EXPECT_EQ(factorization_name(simplicial.kind()), "simplicial-llt");
  EXPECT_GT(simplicial.factor_bytes(), 0u);

  const Eigen::MatrixXd x = cholmod.solve(B), y = simplicial.solve(B);
  Eigen::MatrixXd z;
  simplicial.solve(B, z);
  EXPECT_EQ(y, z); // both entry points run the same simplicial solve
  // Both are backward stable: they agree to the condition number times the unit roundoff. The disk's
  // Laplacian (about 200 rows, shift 1e-3) has a condition number below 1e5, so 1e-10 is a wide margin.
  EXPECT_LE((x - y).norm(), 1e-10 * x.norm());
  EXPECT_LE((A * y - B).norm(), 1e-12 * A.norm() * y.norm()); // backward stable: residual ~ eps |A| |y|

  const SparseCholesky copy = simplicial; // copies keep the threshold and refactorize the same way
  EXPECT_EQ(copy.simplicial_below(), detail::simplicial_free_rows);
  EXPECT_EQ(copy.kind(), FactorizationKind::SimplicialLLT);
  EXPECT_EQ(copy.solve(B), y);

  SparseCholesky above; // at or above the threshold CHOLMOD as before, bit for bit
  above.set_simplicial_below(A.rows());
  above.factorize(A);
  EXPECT_EQ(above.kind(), FactorizationKind::CholmodSupernodalLLT);
  EXPECT_EQ(above.solve(B), x);
}

TEST(ChartSolve, AnIndefiniteSmallSystemFallsBackToLdlt) {
  Eigen::SparseMatrix<double> A = disk_system(4, 12);
  A.coeffRef(0, 0) = -A.coeffRef(0, 0); // one negative pivot: not positive definite, still nonsingular
  SparseCholesky cholesky;
  cholesky.set_simplicial_below(detail::simplicial_free_rows);
  cholesky.factorize(A);
  ASSERT_EQ(cholesky.kind(), FactorizationKind::SimplicialLDLT);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
  const Eigen::VectorXd x = cholesky.solve(b);
  EXPECT_LE((A * x - b).norm(), 1e-9 * b.norm());
}

TEST(ChartSolve, LscmOfASmallDiskMatchesTheCholmodSolveToRounding) {
  // LSCM maps a flat disk onto itself up to a similarity: the map's edge lengths over the mesh's are one
  // constant, whatever factorization solved it; here to 1e-10 (rounding, amplified by the condition).
  const test::TestMesh mesh = test::flat_disk(6, 18);
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  ASSERT_LT(2 * disk.V.rows(), detail::simplicial_free_rows);
  const Eigen::MatrixXd UV = lscm(disk);
  const double ratio = (UV.row(disk.F(0, 1)) - UV.row(disk.F(0, 0))).norm() /
                       (disk.V.row(disk.F(0, 1)) - disk.V.row(disk.F(0, 0))).norm();
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = disk.F(f, k), b = disk.F(f, (k + 1) % 3);
      EXPECT_NEAR((UV.row(b) - UV.row(a)).norm() / (disk.V.row(b) - disk.V.row(a)).norm(), ratio, 1e-10);
    }
}

} // namespace
} // namespace iarap
