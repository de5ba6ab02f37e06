#include "iarap/registration/sample_surface.h"

#include "iarap/core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace iarap {

Eigen::MatrixXd sample_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index count,
                               std::uint32_t seed, double noise) {
  if (count < 0) throw InputError("sample_surface: count is " + std::to_string(count) + "; must be >= 0");
  std::vector<double> cumulative(static_cast<std::size_t>(F.rows()));
  double total = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    total += (b - a).cross(c - a).norm();
    cumulative[static_cast<std::size_t>(f)] = total;
  }
  if (!(total > 0)) throw InputError("sample_surface: the mesh has no face of positive area");
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> gauss(0, noise > 0 ? noise : 1);
  Eigen::MatrixXd P(count, 3);
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto found = std::lower_bound(cumulative.begin(), cumulative.end(), uniform(random) * total);
    const auto f =
        static_cast<Eigen::Index>(std::min<std::ptrdiff_t>(found - cumulative.begin(), F.rows() - 1));
    const double r1 = std::sqrt(uniform(random)), r2 = uniform(random);
    P.row(i) = (1 - r1) * V.row(F(f, 0)) + r1 * (1 - r2) * V.row(F(f, 1)) + r1 * r2 * V.row(F(f, 2));
    if (noise > 0) P.row(i) += Eigen::RowVector3d(gauss(random), gauss(random), gauss(random));
  }
  return P;
}

} // namespace iarap
