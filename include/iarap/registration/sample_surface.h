// Points drawn uniformly by area on a triangle mesh: synthetic scans for registration's tests, examples and
// benchmarks, reproducible from a seed.
#pragma once
#include <Eigen/Core>

#include <cstdint>

namespace iarap {

// count points on (V #V x 3, F #F x 3): a face drawn with probability proportional to its area, then a point
// uniform on it (square-root barycentric warp), from std::mt19937(seed); the same seed gives the same points
// on every platform with the same standard library. noise > 0 adds Gaussian noise of that deviation (mesh
// units) to each coordinate. Throws InputError for a mesh without a face of positive area or count < 0.
Eigen::MatrixXd sample_surface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, Eigen::Index count,
                               std::uint32_t seed, double noise = 0);

} // namespace iarap
