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

namespace {

// Soft constraints are not carried over a repair (face points would need their faces remapped): refused,
// naming where the first one came from, rather than dropped.
TEST(RemapConstraints, SoftConstraintsAreRefusedNotDropped) {
  iarap::ConstraintSet c = three();
  c.soft.vertices = Eigen::VectorXi::Constant(1, 1);
  c.soft.vertex_weights = Eigen::VectorXd::Constant(1, 2.0);
  c.soft.vertex_targets = Eigen::RowVector3d(1, 1, 1);
  c.soft.origins = {"c.txt:4"};
  try {
    iarap::remap_constraints(c, Eigen::VectorXi::LinSpaced(5, 0, 4));
    ADD_FAILURE() << "no error";
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c.txt:4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mesh repair"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("`iarap repair MESH --out REPAIRED"), std::string::npos) << e.what();
  }
}

} // namespace
