// The example scenarios in data/ resolve on the meshes they are written for, into the motions they describe.
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/scenario.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace {

// Resolves data/<scenario> on V and checks: fixed vertices at rest, and each handle's targets a rigid
// motion of its rest positions (pairwise distances kept to rounding, 1e-12 of the bbox diagonal).
iarap::ConstraintSet resolve_and_check(const std::string& scenario_file, const Eigen::MatrixXd& V) {
  const auto scenario = iarap::read_scenario(iarap::test::data_path(scenario_file));
  const auto c = iarap::resolve_scenario(scenario, V);
  const double diagonal = iarap::bounding_box(V).diagonal();
  const auto box = iarap::bounding_box(V);
  std::size_t fixed_count = 0;
  for (const auto& region : scenario.fixed) fixed_count += iarap::select_region(region, V, box).size();
  EXPECT_GT(fixed_count, 0u);
  for (std::size_t k = 0; k < fixed_count; ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    EXPECT_EQ(c.targets.row(row), V.row(c.fixed(row)));
  }
  double worst = 0;
  for (Eigen::Index a = static_cast<Eigen::Index>(fixed_count); a < c.fixed.size(); a += 7) {
    for (Eigen::Index b = a + 1; b < c.fixed.size(); b += 5) {
      const double rest = (V.row(c.fixed(a)) - V.row(c.fixed(b))).norm();
      const double moved = (c.targets.row(a) - c.targets.row(b)).norm();
      worst = std::max(worst, std::abs(rest - moved));
    }
  }
  EXPECT_LT(worst, 1e-12 * diagonal) << scenario_file;
  EXPECT_GT(c.fixed.size(), static_cast<Eigen::Index>(fixed_count)) << scenario_file << ": no handle vertex";
  return c;
}

TEST(BundledScenarios, BunnyScenes) {
  const auto bunny = iarap::read_mesh(iarap::test::data_path("bunny.off"));
  const auto c = resolve_and_check("bunny_scenario.json", bunny.V);
  // The ears turn about their own centroid, so the centroid moves by the translation alone:
  // (0.1, 0.05, 0) bbox diagonals.
  const double diagonal = iarap::bounding_box(bunny.V).diagonal();
  const iarap::BoundingBox box = iarap::bounding_box(bunny.V);
  Eigen::RowVector3d shift = Eigen::RowVector3d::Zero();
  int handle = 0;
  for (Eigen::Index k = 0; k < c.fixed.size(); ++k) {
    if (bunny.V(c.fixed(k), 1) < box.max(1) - 0.1 * (box.max(1) - box.min(1))) continue; // fixed part
    shift += c.targets.row(k) - bunny.V.row(c.fixed(k));
    ++handle;
  }
  ASSERT_GT(handle, 0);
  shift /= handle;
  EXPECT_LT((shift - Eigen::RowVector3d(0.1, 0.05, 0) * diagonal).norm(), 1e-12 * diagonal) << shift;
  resolve_and_check("bunny_twist.json", bunny.V);
  resolve_and_check("bunny_sphere_handle.json", bunny.V);
}

TEST(BundledScenarios, PaperFigureScenesOnSharedMeshes) {
  IARAP_SHARED_MESH_OR_SKIP(cube, "cube.obj");
  IARAP_SHARED_MESH_OR_SKIP(grid, "grid.off");
  resolve_and_check("cube_push_back.json", iarap::read_mesh(cube).V);
  resolve_and_check("plane_lift.json", iarap::read_mesh(grid).V);
}

} // namespace
