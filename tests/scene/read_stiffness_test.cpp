#include "iarap/scene/read_stiffness.h"

#include "iarap/core/errors.h"

#include <gtest/gtest.h>

#include <sstream>

namespace {

Eigen::VectorXd stiffness_from_text(const std::string& text, int num_vertices = 10) {
  std::istringstream in(text);
  return iarap::parse_stiffness(in, "s.txt", num_vertices);
}

// Expects an InputError whose message contains every fragment.
void expect_stiffness_error(const std::string& text, const std::vector<std::string>& fragments) {
  try {
    stiffness_from_text(text);
    FAIL() << "no error for:\n" << text;
  } catch (const iarap::InputError& e) {
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ReadStiffness, NamedVerticesGetTheirFactorOthersOne) {
  const Eigen::VectorXd s = stiffness_from_text("# header\n\n3 2.5\n  7\t1e6  # a stiff one\n");
  ASSERT_EQ(s.size(), 10);
  EXPECT_EQ(s(3), 2.5);
  EXPECT_EQ(s(7), 1e6);
  EXPECT_EQ(s.sum(), 8 + 2.5 + 1e6);
}

TEST(ReadStiffness, BadLinesNameFileAndLine) {
  expect_stiffness_error("1 2\n3\n", {"s.txt:2:", "expected 'index s'", "1 token"});
  expect_stiffness_error("10 2\n", {"s.txt:1:", "out of range", "10 vertices"});
  expect_stiffness_error("-1 2\n", {"s.txt:1:", "out of range"});
  expect_stiffness_error("1 0\n", {"s.txt:1:", "not > 0"});
  expect_stiffness_error("1 -3\n", {"s.txt:1:", "not > 0"});
  expect_stiffness_error("1 nan\n", {"s.txt:1:"});
  expect_stiffness_error("1 x\n", {"s.txt:1:"});
  expect_stiffness_error("1 2\n# again\n1 3\n", {"s.txt:3:", "vertex 1", "line 1"});
  expect_stiffness_error("# nothing\n\n", {"s.txt", "no stiffness"});
}

TEST(ReadStiffness, MissingFileIsNamed) {
  try {
    iarap::read_stiffness("/nonexistent/stiff.txt", 4);
    FAIL();
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/stiff.txt"), std::string::npos);
  }
}

} // namespace
