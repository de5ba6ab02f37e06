#include "iarap/scene/read_constraints.h"

#include "iarap/core/errors.h"

#include <gtest/gtest.h>

#include <sstream>

namespace {

iarap::ConstraintSet constraints_from_text(const std::string& text, int num_vertices = 10) {
  std::istringstream in(text);
  return iarap::parse_constraints(in, "c.txt", num_vertices, 4); // 4 faces for the 'b' lines
}

// Expects an InputError whose message contains every fragment.
void expect_constraints_error(const std::string& text, const std::vector<std::string>& fragments,
                              int num_vertices = 10) {
  try {
    constraints_from_text(text, num_vertices);
    FAIL() << "no error for:\n" << text;
  } catch (const iarap::InputError& e) {
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ReadConstraints, ParsesLinesCommentsAndBlanks) {
  const auto c =
      constraints_from_text("# header\n\n3 1 2 3\n  7\t-1e-3 0 4.5  # trailing comment\n0 0 0 0\n");
  ASSERT_EQ(c.fixed.size(), 3);
  EXPECT_EQ(c.fixed(0), 3);
  EXPECT_EQ(c.fixed(1), 7);
  EXPECT_EQ(c.fixed(2), 0);
  EXPECT_EQ(c.targets.row(0), Eigen::RowVector3d(1, 2, 3));
  EXPECT_EQ(c.targets.row(1), Eigen::RowVector3d(-1e-3, 0, 4.5));
  EXPECT_TRUE(c.warnings.empty());
}

TEST(ReadConstraints, IdenticalDuplicateIsMergedWithWarning) {
  const auto c = constraints_from_text("1 0 0 1\n2 0 0 0\n1 0 0 1\n");
  ASSERT_EQ(c.fixed.size(), 2);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("c.txt:3"), std::string::npos) << c.warnings[0];
}

TEST(ReadConstraints, ConflictingDuplicateNamesBothLines) {
  expect_constraints_error("1 0 0 1\n\n1 0 0 2\n", {"c.txt:3", "vertex 1", "line 1", "different target"});
}

TEST(ReadConstraints, IndexOutOfRangeGivesMeshSize) {
  expect_constraints_error("0 0 0 0\n10 0 0 0\n", {"c.txt:2", "10", "mesh has 10 vertices"});
  expect_constraints_error("-1 0 0 0\n", {"c.txt:1", "out of range"});
}

TEST(ReadConstraints, NonFiniteCoordinates) {
  expect_constraints_error("0 nan 0 0\n", {"c.txt:1", "non-finite x"});
  expect_constraints_error("0 0 0 inf\n", {"c.txt:1", "non-finite z"});
  expect_constraints_error("0 0 1e999 0\n", {"c.txt:1", "non-finite y"});
}

TEST(ReadConstraints, BadTokens) {
  expect_constraints_error("1.5 0 0 0\n", {"c.txt:1", "bad vertex index '1.5'"});
  expect_constraints_error("abc 0 0 0\n", {"c.txt:1", "bad vertex index"});
  expect_constraints_error("1 0 0x 0\n", {"c.txt:1", "bad y coordinate '0x'"});
  expect_constraints_error("1 0\n", {"c.txt:1", "found 2 token"});
  expect_constraints_error("1 0 0 0 5 6\n", {"c.txt:1", "found 6 token"}); // 5 tokens: a soft vertex
}

// 'index x y' is a target in the plane z = 0, for planar meshes; the two forms mix.
TEST(ReadConstraints, TwoCoordinatesAreATargetInThePlane) {
  const auto c = constraints_from_text("3 1.5 -2\n4 1 2 3\n");
  ASSERT_EQ(c.fixed.size(), 2);
  EXPECT_EQ(c.targets.row(0), Eigen::RowVector3d(1.5, -2, 0));
  EXPECT_EQ(c.targets.row(1), Eigen::RowVector3d(1, 2, 3));
  expect_constraints_error("3 1 nan\n", {"c.txt:1", "non-finite y"});
}

TEST(ReadConstraints, EmptySet) {
  expect_constraints_error("", {"c.txt", "no constraints"});
  expect_constraints_error("# only a comment\n\n", {"c.txt", "no constraints"});
}

// Issue 32: 'INDEX X Y Z W' soft vertices and 'b FACE B0 B1 B2 X Y Z W' soft face points, apart from the
// hard ones and in file order.
TEST(ReadConstraints, SoftVerticesAndFacePoints) {
  const auto c =
      constraints_from_text("3 1 2 3\n5 0 1 0 2.5\nb 2 0.25 0.25 0.5 1 1 1 1e8\n4 0 0 1\n6 1 1 1 1e-3\n");
  ASSERT_EQ(c.fixed.size(), 2);
  EXPECT_EQ(c.fixed(0), 3);
  EXPECT_EQ(c.fixed(1), 4);
  ASSERT_EQ(c.soft.vertices.size(), 2);
  EXPECT_EQ(c.soft.vertices(0), 5);
  EXPECT_EQ(c.soft.vertices(1), 6);
  EXPECT_EQ(c.soft.vertex_weights(0), 2.5);
  EXPECT_EQ(c.soft.vertex_weights(1), 1e-3);
  EXPECT_EQ(c.soft.vertex_targets.row(0), Eigen::RowVector3d(0, 1, 0));
  ASSERT_EQ(c.soft.faces.size(), 1);
  EXPECT_EQ(c.soft.faces(0), 2);
  EXPECT_EQ(c.soft.barycentric.row(0), Eigen::RowVector3d(0.25, 0.25, 0.5));
  EXPECT_EQ(c.soft.face_weights(0), 1e8);
  EXPECT_EQ(c.soft.face_targets.row(0), Eigen::RowVector3d(1, 1, 1));
  ASSERT_EQ(c.soft.origins.size(), 3u);
  EXPECT_EQ(c.soft.origins[0], "c.txt:2");
  EXPECT_EQ(c.soft.origins[2], "c.txt:3");
  // Soft constraints alone are a constraint set.
  EXPECT_EQ(constraints_from_text("5 0 1 0 2.5\n").soft.size(), 1);
}

// 'b FACE B0 B1 B2 X Y Z' without a weight is a hard point; its origin follows the soft ones'.
TEST(ReadConstraints, HardFacePoints) {
  const auto c =
      constraints_from_text("b 1 0.2 0.3 0.5 1 2 3\nb 2 0.25 0.25 0.5 1 1 1 4\n0 0 0 0\nb 3 1 0 0 -1 0 0\n");
  EXPECT_EQ(c.fixed.size(), 1);
  ASSERT_EQ(c.soft.faces.size(), 1);
  EXPECT_EQ(c.soft.faces(0), 2);
  ASSERT_EQ(c.soft.hard_faces.size(), 2);
  EXPECT_EQ(c.soft.hard_faces(0), 1);
  EXPECT_EQ(c.soft.hard_faces(1), 3);
  EXPECT_EQ(c.soft.hard_barycentric.row(0), Eigen::RowVector3d(0.2, 0.3, 0.5));
  EXPECT_EQ(c.soft.hard_targets.row(1), Eigen::RowVector3d(-1, 0, 0));
  EXPECT_EQ(c.soft.size(), 3);
  ASSERT_EQ(c.soft.origins.size(), 3u);
  EXPECT_EQ(c.soft.origins[0], "c.txt:2");
  EXPECT_EQ(c.soft.origins[1], "c.txt:1");
  EXPECT_EQ(c.soft.origins[2], "c.txt:4");
  // Hard points alone are a constraint set.
  EXPECT_EQ(constraints_from_text("b 1 0.2 0.3 0.5 1 2 3\n").soft.hard_faces.size(), 1);
}

TEST(ReadConstraints, BadSoftConstraintsNameTheLine) {
  expect_constraints_error("1 0 0 0 0\n", {"c.txt:1", "weight 0 must be > 0"});
  expect_constraints_error("1 0 0 0\n2 0 0 0 -1\n", {"c.txt:2", "weight -1 must be > 0"});
  expect_constraints_error("1 0 0 0 nan\n", {"c.txt:1", "non-finite weight"});
  expect_constraints_error("1 0 0 0 w\n", {"c.txt:1", "bad weight"});
  expect_constraints_error("1 0 0 0\n1 0 0 0 2\n",
                           {"c.txt:2", "vertex 1", "line 1", "one constraint, hard or soft"});
  expect_constraints_error("1 0 0 0 2\n1 0 0 0 2\n", {"c.txt:2", "line 1 (soft)"});
  expect_constraints_error("b 4 1 0 0 0 0 0 1\n", {"c.txt:1", "face index 4 out of range", "4 faces"});
  expect_constraints_error("b -1 1 0 0 0 0 0 1\n", {"c.txt:1", "face index -1 out of range"});
  expect_constraints_error("b x 1 0 0 0 0 0 1\n", {"c.txt:1", "bad face index 'x'"});
  expect_constraints_error("\nb 0 0.5 0.5 0.1 0 0 0 1\n", {"c.txt:2", "sum to 1.1", "within 1e-9"});
  expect_constraints_error("b 0 0.5 0.5 nan 0 0 0 1\n", {"c.txt:1", "non-finite b2 barycentric"});
  expect_constraints_error("b 0 1 0 0 0 0 0 0\n", {"c.txt:1", "weight 0 must be > 0"});
  expect_constraints_error("b 0 1 0 0 0 0\n",
                           {"c.txt:1", "expected 'b face b0 b1 b2 x y z' (hard)", "found 7 token"});
  expect_constraints_error("b 0 0.5 0.6 0 0 0 0\n",
                           {"c.txt:1", "sum to 1.1"}); // hard points are checked alike
  // Within 1e-9 passes.
  EXPECT_EQ(constraints_from_text("b 0 0.3333333333 0.3333333333 0.3333333334 0 0 0 1\n").soft.faces.size(),
            1);
}

TEST(ReadConstraints, MissingFile) {
  EXPECT_THROW(iarap::read_constraints("/nonexistent/constraints.txt", 10), iarap::InputError);
}

} // namespace
