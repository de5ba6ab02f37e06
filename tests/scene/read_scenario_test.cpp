#include "iarap/scene/read_scenario.h"

#include "iarap/core/errors.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

void expect_scenario_error(const std::string& text, const std::vector<std::string>& fragments) {
  try {
    iarap::parse_scenario(text, "s.json");
    FAIL() << "no error for: " << text;
  } catch (const iarap::InputError& e) {
    for (const auto& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ReadScenario, ParsesEveryRegionKindAndMotion) {
  const auto s = iarap::parse_scenario(R"({
    "description": "all kinds",
    "fixed": [ [1, 2], {"indices": [3]}, {"bottom": 0.1, "axis": "z"},
               {"box": {"min": [0, 0, 0], "max": [1, 0.5, 1], "relative": true}},
               {"sphere": {"center": [1, 2, 3], "radius": 0.5}} ],
    "handles": [ {"name": "head", "vertices": {"top": 0.2},
                  "translate_relative": [0.1, 0, 0],
                  "rotate": {"axis": "y", "degrees": 30, "center_relative": [0.5, 1, 0.5]}},
                 {"vertices": [7, 8], "translate": [1, 2, 3], "rotate": {"axis": [0, 0, 2], "degrees": -5}} ]
  })",
                                       "s.json");
  EXPECT_EQ(s.description, "all kinds");
  EXPECT_EQ(s.source, "s.json");
  ASSERT_EQ(s.fixed.size(), 5u);
  EXPECT_EQ(s.fixed[0].kind, iarap::RegionKind::Indices);
  EXPECT_EQ(s.fixed[0].indices, (std::vector<int>{1, 2}));
  EXPECT_EQ(s.fixed[1].indices, (std::vector<int>{3}));
  EXPECT_EQ(s.fixed[2].kind, iarap::RegionKind::Bottom);
  EXPECT_EQ(s.fixed[2].axis, 2);
  EXPECT_EQ(s.fixed[2].fraction, 0.1);
  EXPECT_EQ(s.fixed[3].kind, iarap::RegionKind::Box);
  EXPECT_TRUE(s.fixed[3].relative);
  EXPECT_EQ(s.fixed[3].hi, Eigen::Vector3d(1, 0.5, 1));
  EXPECT_EQ(s.fixed[4].kind, iarap::RegionKind::Sphere);
  EXPECT_FALSE(s.fixed[4].relative);
  EXPECT_EQ(s.fixed[4].radius, 0.5);
  EXPECT_EQ(s.fixed[4].path, "s.json: $.fixed[4]");
  ASSERT_EQ(s.handles.size(), 2u);
  const auto& head = s.handles[0];
  EXPECT_EQ(head.name, "head");
  EXPECT_EQ(head.vertices[0].kind, iarap::RegionKind::Top);
  EXPECT_EQ(head.vertices[0].axis, 1); // default axis y
  EXPECT_TRUE(head.translation_relative);
  EXPECT_EQ(head.rotation_axis, Eigen::Vector3d::UnitY());
  EXPECT_EQ(head.rotation_degrees, 30);
  ASSERT_TRUE(head.rotation_center.has_value());
  EXPECT_TRUE(head.rotation_center_relative);
  const auto& second = s.handles[1];
  EXPECT_EQ(second.vertices[0].indices, (std::vector<int>{7, 8}));
  EXPECT_FALSE(second.translation_relative);
  EXPECT_EQ(second.translation, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(second.rotation_center.has_value());
  EXPECT_EQ(second.path, "s.json: $.handles[1]");
}

TEST(ReadScenario, SyntaxErrorGivesLineAndColumn) {
  expect_scenario_error("{\n  \"fixed\": [1, 2,\n}", {"s.json", "parse error at line 3"});
}

// A planar scene may give points and offsets as [x, y] (z = 0); a rotation axis stays three numbers.
TEST(ReadScenario, TwoNumbersArePointsInThePlane) {
  const auto s = iarap::parse_scenario(R"({
    "fixed": {"sphere": {"center": [0.5, 0.25], "radius": 0.1}},
    "handles": [ {"vertices": [4], "translate": [1, 2], "rotate": {"axis": "z", "degrees": 10,
                  "center": [0.5, 0.5]}} ]
  })",
                                       "s.json");
  EXPECT_EQ(s.fixed[0].center, Eigen::Vector3d(0.5, 0.25, 0));
  EXPECT_EQ(s.handles[0].translation, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(s.handles[0].rotation_center, Eigen::Vector3d(0.5, 0.5, 0));
}

TEST(ReadScenario, ErrorsNameTheJsonPath) {
  expect_scenario_error(R"({"fixed": [1], "handels": []})", {"s.json: $: unknown key 'handels'"});
  expect_scenario_error(R"({"fixed": {"bottom": 1.5}})", {"$.fixed.bottom: fraction must be in (0, 1]"});
  expect_scenario_error(R"({"fixed": {"bottom": 0.1, "axis": "w"}})", {"$.fixed.axis", "\"w\""});
  expect_scenario_error(
      R"({"fixed": [0], "handles": [{"vertices": [1], "rotate": {"axis": [0, 0], "degrees": 3}}]})",
      {"$.handles[0].rotate.axis: expected an array of 3 numbers"});
  expect_scenario_error(
      R"({"fixed": [0], "handles": [{"vertices": [1], "rotate": {"axis": [0, 0, 0], "degrees": 3}}]})",
      {"$.handles[0].rotate.axis: rotation axis must be non-zero"});
  expect_scenario_error(R"({"fixed": [0], "handles": [{"vertices": [1], "translate": [1, 2, "x"]}]})",
                        {"$.handles[0].translate[2]: expected a number"});
  expect_scenario_error(R"({"fixed": [0], "handles": [{"translate": [1, 2, 3]}]})",
                        {"$.handles[0]: a handle needs"});
  expect_scenario_error(R"({"fixed": [0, -3]})", {"$.fixed[1]", "out of range"});
  expect_scenario_error(R"({"fixed": [0, 1.5]})", {"$.fixed[1]", "expected a vertex index"});
  expect_scenario_error(R"({"fixed": {"box": {"min": [1, 0, 0], "max": [0, 1, 1]}}})",
                        {"$.fixed.box: min exceeds max"});
  expect_scenario_error(R"({"fixed": {"cylinder": 1}})", {"$.fixed: a region needs one of"});
  // Keys a region needs (found by the fuzz test: json's out_of_range escaped as a non-input error).
  expect_scenario_error(R"({"fixed": {"box": {"min": [0, 0, 0]}}})", {"$.fixed.box: missing key 'max'"});
  expect_scenario_error(R"({"fixed": {"sphere": {"radius": 1}}})", {"$.fixed.sphere: missing key 'center'"});
  expect_scenario_error(R"({"fixed": {"sphere": {"center": [0, 0, 0]}}})",
                        {"$.fixed.sphere: missing key 'radius'"});
  expect_scenario_error(R"({"description": "nothing"})", {"s.json: $: a scenario needs"});
  expect_scenario_error(R"([1, 2])", {"s.json: $: expected an object"});
}

TEST(ReadScenario, BundledExamplesParse) {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(IARAP_SOURCE_DIR) + "/data")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const auto s = iarap::read_scenario(entry.path().string());
    EXPECT_FALSE(s.description.empty());
  }
}

TEST(ReadScenario, MissingFile) {
  try {
    iarap::read_scenario("/nonexistent/s.json");
    FAIL();
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/s.json: cannot open"), std::string::npos);
  }
}

} // namespace
