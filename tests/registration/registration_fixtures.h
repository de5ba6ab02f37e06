// Fixtures of the registration tests: a known ARAP deformation of the bundled bunny.
#pragma once
#include "iarap/core/threads.h"
#include "iarap/io/read_mesh.h"
#include "iarap/registration/sample_surface.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/solver/arap.h"
#include "test_support.h"

namespace iarap::test {

// One thread for the scope, as the tool runs meshes below 10,000 vertices (a thread team on a loaded machine
// made the bunny's registration 9x slower), then back to all.
struct OneThread {
  OneThread() { set_thread_count(1); }
  ~OneThread() { set_thread_count(0); }
  OneThread(const OneThread&) = delete;
  OneThread& operator=(const OneThread&) = delete;
};

// data/bunny.off and its ARAP (iARAP) deformation under data/bunny_constraints.txt (bottom fixed, ears
// moved by a tenth of the diagonal): the known answer registration should find again.
struct KnownDeformation {
  MeshData mesh;
  Eigen::MatrixXd U; // #V x 3
  double diagonal = 0;
};

inline KnownDeformation bunny_deformation() {
  KnownDeformation known;
  known.mesh = read_mesh(data_path("bunny.off"));
  const ConstraintSet set =
      read_constraints(data_path("bunny_constraints.txt"), static_cast<int>(known.mesh.V.rows()));
  ArapData data = arap_precompute(known.mesh.V, known.mesh.F, set.fixed);
  known.U = known.mesh.V;
  arap_solve(data, set.targets, known.U);
  known.diagonal = (known.mesh.V.colwise().maxCoeff() - known.mesh.V.colwise().minCoeff()).norm();
  return known;
}

// Mean |A_i - B_i| over the rows.
inline double mean_row_distance(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  return (A - B).rowwise().norm().mean();
}

} // namespace iarap::test
