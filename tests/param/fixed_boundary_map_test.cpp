// Tutte's and the harmonic map: injectivity of Tutte's on a curved disk, linear precision of the cotan
// weights on a planar one, and the circular boundary.
#include "iarap/param/fixed_boundary_map.h"

#include "iarap/core/errors.h"
#include "iarap/param/map_distortion.h"
#include "param/disk_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace iarap {
namespace {

TEST(CircleBoundary, ArcLengthSpacingOnACircleOfTheSurfacesArea) {
  const test::TestMesh mesh = test::flat_square(3); // boundary of 12 edges of length 1/3
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  const Eigen::MatrixXd uv = circle_boundary(disk);
  const double radius = std::sqrt(1.0 / M_PI);
  ASSERT_EQ(uv.rows(), 12);
  for (Eigen::Index p = 0; p < 12; ++p) {
    EXPECT_NEAR(uv.row(p).norm(), radius, 1e-15);
    EXPECT_NEAR(std::atan2(uv(p, 1), uv(p, 0)), std::remainder(2 * M_PI * p / 12, 2 * M_PI), 1e-14);
  }
}

TEST(FixedBoundaryMap, TutteOfACurvedDiskIsInjective) {
  // A cap of half a sphere with random vertex offsets: the cotan weights go negative in places, the uniform
  // ones never do, and Tutte's theorem (convex boundary, positive weights) gives det J > 0 everywhere.
  test::TestMesh mesh = test::spherical_cap(6, 13, 0.5 * M_PI);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> offset(-0.03, 0.03);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k) mesh.V(v, k) += offset(random);
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  const Eigen::MatrixXd boundary = circle_boundary(disk);
  const Eigen::MatrixXd UV = fixed_boundary_map(disk, BoundaryMapWeights::Uniform, boundary);
  const MapDistortion distortion = map_distortion(disk.frames, disk.F, UV);
  EXPECT_EQ(distortion.flipped, 0);
  EXPECT_GT(distortion.min_det_J, 0);
  for (std::size_t p = 0; p < disk.boundary.size(); ++p)
    EXPECT_EQ(UV.row(disk.boundary[p]), boundary.row(static_cast<Eigen::Index>(p)));
  // Each inner vertex is the average of its neighbours: the uniform Laplacian vanishes there.
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(UV.rows(), 2);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(UV.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) { // each interior edge is seen from its two faces: both directions, twice
      sum.row(mesh.F(f, k)) += UV.row(mesh.F(f, (k + 1) % 3)) + UV.row(mesh.F(f, (k + 2) % 3));
      count(mesh.F(f, k)) += 2;
    }
  std::vector<char> on_boundary(static_cast<std::size_t>(UV.rows()), 0);
  for (int v : disk.boundary) on_boundary[static_cast<std::size_t>(v)] = 1;
  for (Eigen::Index v = 0; v < UV.rows(); ++v) {
    if (on_boundary[static_cast<std::size_t>(v)]) continue;
    EXPECT_LT((UV.row(v) - sum.row(v) / count(v)).norm(), 1e-12) << "vertex " << v;
  }
}

TEST(FixedBoundaryMap, HarmonicReproducesAPlanarMesh) {
  // Linear precision: with the boundary at its own positions, the cotan-weighted average of a planar mesh
  // is the identity, on an irregular triangulation too.
  test::TestMesh mesh = test::flat_disk(4, 12);
  std::mt19937 random(9);
  std::uniform_real_distribution<double> offset(-0.04, 0.04);
  for (Eigen::Index v = 1; v < mesh.V.rows() - 12; ++v) // inner vertices only; the boundary stays convex
    for (int k = 0; k < 2; ++k) mesh.V(v, k) += offset(random);
  const DiskMesh disk = prepare_disk(mesh.V, mesh.F);
  Eigen::MatrixXd boundary(static_cast<Eigen::Index>(disk.boundary.size()), 2);
  for (std::size_t p = 0; p < disk.boundary.size(); ++p)
    boundary.row(static_cast<Eigen::Index>(p)) = mesh.V.row(disk.boundary[p]).head<2>();
  const Eigen::MatrixXd UV = fixed_boundary_map(disk, BoundaryMapWeights::Cotan, boundary);
  EXPECT_LT((UV - mesh.V.leftCols(2)).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_THROW(fixed_boundary_map(disk, BoundaryMapWeights::Cotan, boundary.topRows(3)), InputError);
}

} // namespace
} // namespace iarap
