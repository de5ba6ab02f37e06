#include "iarap/scene/remap_constraints.h"

#include "iarap/core/errors.h"

#include <gtest/gtest.h>

namespace {

iarap::ConstraintSet three() {
  iarap::ConstraintSet c;
  c.fixed.resize(3);
  c.fixed << 0, 2, 4;
  c.targets.resize(3, 3);
  c.targets << 0, 0, 0, 2, 2, 2, 4, 4, 4;
  return c;
}

TEST(RemapConstraints, FollowsRenumbering) {
  Eigen::VectorXi old_to_new(5);
  old_to_new << 3, -1, 0, 1, 2;
  const auto c = iarap::remap_constraints(three(), old_to_new);
  ASSERT_EQ(c.fixed.size(), 3);
  EXPECT_EQ(c.fixed, Eigen::Vector3i(3, 0, 2));
  EXPECT_EQ(c.targets, three().targets);
}

TEST(RemapConstraints, RemovedVertexIsAnError) {
  Eigen::VectorXi old_to_new(5);
  old_to_new << 0, 1, -1, 2, 3;
  try {
    iarap::remap_constraints(three(), old_to_new);
    FAIL();
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("constrained vertex 2 was removed"), std::string::npos) << e.what();
  }
}

TEST(RemapConstraints, MergedVerticesMustAgree) {
  Eigen::VectorXi old_to_new(5);
  old_to_new << 0, 1, 0, 2, 3; // 0 and 2 welded
  EXPECT_THROW(iarap::remap_constraints(three(), old_to_new), iarap::InputError);
  auto same = three();
  same.targets.row(1) = same.targets.row(0);
  const auto c = iarap::remap_constraints(same, old_to_new);
  EXPECT_EQ(c.fixed.size(), 2);
}

} // namespace
