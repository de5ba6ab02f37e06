#include "iarap/scene/read_rigid_groups.h"

#include "iarap/core/errors.h"
#include "io/mesh_file_fixtures.h"

#include <gtest/gtest.h>

#include <sstream>

namespace {

std::vector<std::vector<int>> parse(const std::string& text, int num_vertices = 10) {
  std::istringstream in(text);
  return iarap::parse_rigid_groups(in, "g.txt", num_vertices);
}

// Expects an InputError whose message contains every part.
void expect_rigid_groups_error(const std::string& text, std::initializer_list<std::string> parts) {
  iarap::test::expect_input_error([&] { parse(text); }, parts);
}

TEST(ReadRigidGroups, OneGroupPerLineCommentsSkipped) {
  const auto groups = parse("# two parts\n0 1 2\n  7\t9 3  # the other one\n");
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(groups[1], (std::vector<int>{7, 9, 3}));
}

TEST(ReadRigidGroups, BadLinesNameFileAndLine) {
  expect_rigid_groups_error("0 1\n\n2 3\n", {"g.txt:2:", "empty line"});
  expect_rigid_groups_error("0 1\n   \n", {"g.txt:2:", "empty line"});
  expect_rigid_groups_error("0 1\n4\n", {"g.txt:2:", "1 vertex"});
  expect_rigid_groups_error("0 10\n", {"g.txt:1:", "out of range", "10 vertices"});
  expect_rigid_groups_error("0 -1\n", {"g.txt:1:", "out of range"});
  expect_rigid_groups_error("0 x\n", {"g.txt:1:", "bad vertex index 'x'"});
  expect_rigid_groups_error("0 1.5\n", {"g.txt:1:", "bad vertex index '1.5'"});
  expect_rigid_groups_error("0 1 0\n", {"g.txt:1:", "vertex 0 is named twice"});
  expect_rigid_groups_error("0 1\n# gap\n2 1\n",
                            {"g.txt:3:", "vertex 1 is already in the rigid group of line 1"});
  expect_rigid_groups_error("# nothing\n", {"g.txt", "no rigid group"});
}

TEST(ReadRigidGroups, MissingFileIsNamed) {
  iarap::test::expect_input_error([] { iarap::read_rigid_groups("/nonexistent/groups.txt", 10); },
                                  {"/nonexistent/groups.txt", "cannot open"});
}

} // namespace
