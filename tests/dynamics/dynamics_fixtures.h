// A curved patch held at its bottom 10% along y, the scene of the dynamics and statics tests.
#pragma once
#include "solver/solver_fixtures.h"

#include <Eigen/Core>
#include <vector>

namespace iarap::test {

struct HeldPatch {
  SolverMesh mesh;
  Eigen::VectorXi fixed;   // the vertices with y <= 0.1 (the patch spans [0, 1] in y)
  Eigen::MatrixXd targets; // their rest positions
  double diagonal = 0;     // of the bounding box
};

inline HeldPatch held_patch(const SolverMesh& mesh) {
  HeldPatch p;
  p.mesh = mesh;
  std::vector<int> fixed;
  for (Eigen::Index v = 0; v < p.mesh.V.rows(); ++v)
    if (p.mesh.V(v, 1) <= 0.1) fixed.push_back(static_cast<int>(v));
  p.fixed = Eigen::Map<Eigen::VectorXi>(fixed.data(), static_cast<Eigen::Index>(fixed.size()));
  p.targets.resize(p.fixed.size(), 3);
  for (Eigen::Index k = 0; k < p.fixed.size(); ++k) p.targets.row(k) = p.mesh.V.row(p.fixed(k));
  p.diagonal = (p.mesh.V.colwise().maxCoeff() - p.mesh.V.colwise().minCoeff()).norm();
  return p;
}

inline HeldPatch held_patch(int n) {
  return held_patch(bumpy_patch(n));
}

} // namespace iarap::test
