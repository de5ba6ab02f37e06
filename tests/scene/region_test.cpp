#include "iarap/scene/region.h"

#include "iarap/core/errors.h"

#include <gtest/gtest.h>

#include <limits>

namespace {

// Points 0..10 along y at x = z = 0, plus one off-axis point, plus a NaN row ignored by the box.
Eigen::MatrixXd line_points() {
  Eigen::MatrixXd V(13, 3);
  for (int i = 0; i <= 10; ++i) V.row(i) << 0, i, 0;
  V.row(11) << 4, 5, 0;
  V.row(12) << std::numeric_limits<double>::quiet_NaN(), 0, 0;
  return V;
}

TEST(Region, BoundingBoxIgnoresNonFiniteRows) {
  const auto box = iarap::bounding_box(line_points());
  EXPECT_EQ(box.min, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(4, 10, 0));
}

TEST(Region, BottomAndTopSlabs) {
  const auto V = line_points();
  const auto box = iarap::bounding_box(V);
  iarap::Region bottom;
  bottom.kind = iarap::RegionKind::Bottom;
  bottom.fraction = 0.25; // y <= 2.5
  EXPECT_EQ(iarap::select_region(bottom, V, box), (std::vector<int>{0, 1, 2}));
  iarap::Region top = bottom;
  top.kind = iarap::RegionKind::Top; // y >= 7.5
  EXPECT_EQ(iarap::select_region(top, V, box), (std::vector<int>{8, 9, 10}));
  top.axis = 0; // x >= 3
  EXPECT_EQ(iarap::select_region(top, V, box), (std::vector<int>{11}));
}

TEST(Region, BoxAbsoluteAndRelative) {
  const auto V = line_points();
  const auto box = iarap::bounding_box(V);
  iarap::Region r;
  r.kind = iarap::RegionKind::Box;
  r.lo = Eigen::Vector3d(-1, 3, -1);
  r.hi = Eigen::Vector3d(1, 5, 1);
  EXPECT_EQ(iarap::select_region(r, V, box), (std::vector<int>{3, 4, 5}));
  r.relative = true; // x in [0, 1] of [0, 4], y in [0.3, 0.5] of [0, 10]
  r.lo = Eigen::Vector3d(0, 0.3, 0);
  r.hi = Eigen::Vector3d(1, 0.5, 1);
  EXPECT_EQ(iarap::select_region(r, V, box), (std::vector<int>{3, 4, 5, 11}));
}

TEST(Region, SphereAbsoluteAndRelative) {
  const auto V = line_points();
  const auto box = iarap::bounding_box(V);
  iarap::Region r;
  r.kind = iarap::RegionKind::Sphere;
  r.center = Eigen::Vector3d(0, 5, 0);
  r.radius = 1;
  EXPECT_EQ(iarap::select_region(r, V, box), (std::vector<int>{4, 5, 6}));
  r.relative = true; // centre (0, 10, 0); radius 0.1 * sqrt(116) = 1.077
  r.center = Eigen::Vector3d(0, 1, 0);
  r.radius = 0.1;
  EXPECT_EQ(iarap::select_region(r, V, box), (std::vector<int>{9, 10}));
}

TEST(Region, IndicesAreSortedAndDeduplicated) {
  const auto V = line_points();
  iarap::Region r;
  r.indices = {5, 2, 5};
  EXPECT_EQ(iarap::select_region(r, V, iarap::bounding_box(V)), (std::vector<int>{2, 5}));
}

TEST(Region, ErrorsNameThePath) {
  const auto V = line_points();
  const auto box = iarap::bounding_box(V);
  iarap::Region r;
  r.path = "s.json: $.fixed";
  r.indices = {13};
  try {
    iarap::select_region(r, V, box);
    FAIL();
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: $.fixed: vertex index 13 out of range; the mesh has 13"),
              std::string::npos)
        << e.what();
  }
  r.kind = iarap::RegionKind::Sphere;
  r.center = Eigen::Vector3d(100, 0, 0);
  r.radius = 1;
  try {
    iarap::select_region(r, V, box);
    FAIL();
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: $.fixed: selects no vertex"), std::string::npos)
        << e.what();
  }
}

} // namespace
