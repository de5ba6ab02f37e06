// Fixtures of the registration tests: a known ARAP deformation of the bundled bunny and noisy samples of a
// surface (fixed seed).
#pragma once
#include "iarap/io/read_mesh.h"
#include "iarap/scene/read_constraints.h"
#include "iarap/solver/arap.h"
#include "test_support.h"

#include <Eigen/Geometry>

#include <random>

namespace iarap::test {

// `count` points drawn uniformly by area on the mesh (V, F), each moved by Gaussian noise of deviation
// `noise` (mesh units) along every axis; fixed seed.
inline Eigen::MatrixXd sample_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int count,
                                      double noise, unsigned seed = 46) {
  std::vector<double> cumulative(static_cast<std::size_t>(F.rows()));
  double total = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    total += (b - a).cross(c - a).norm();
    cumulative[static_cast<std::size_t>(f)] = total;
  }
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> gauss(0, 1);
  Eigen::MatrixXd P(count, 3);
  for (int i = 0; i < count; ++i) {
    const auto f = static_cast<Eigen::Index>(
        std::lower_bound(cumulative.begin(), cumulative.end(), uniform(random) * total) - cumulative.begin());
    double r1 = std::sqrt(uniform(random)), r2 = uniform(random);
    const Eigen::RowVector3d p =
        (1 - r1) * V.row(F(f, 0)) + r1 * (1 - r2) * V.row(F(f, 1)) + r1 * r2 * V.row(F(f, 2));
    P.row(i) = p + noise * Eigen::RowVector3d(gauss(random), gauss(random), gauss(random));
  }
  return P;
}

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
