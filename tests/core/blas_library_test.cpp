#include "iarap/core/blas_library.h"

#include "iarap/solver/sparse_cholesky.h"

#include <gtest/gtest.h>

// CHOLMOD links the BLAS, so it is loaded in every process that links iarap: the report can always name it.
TEST(BlasLibrary, NamesTheLoadedBlas) {
  const iarap::SparseCholesky chol(Eigen::SparseMatrix<double>(Eigen::MatrixXd::Identity(4, 4).sparseView()));
  EXPECT_NE(iarap::blas_library_path(), "unknown");
  const std::string name = iarap::blas_library_name();
  EXPECT_FALSE(name.empty());
  EXPECT_NE(name, "unknown");
  iarap::limit_blas_threads(1); // a no-op for a single-threaded BLAS, a cap for OpenBLAS: never a crash
  iarap::limit_blas_threads(0); // clamped to 1
}
