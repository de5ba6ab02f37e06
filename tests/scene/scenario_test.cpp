#include "iarap/scene/scenario.h"

#include "iarap/core/errors.h"
#include "iarap/scene/read_scenario.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace {

// A 5 x 5 grid in the xy-plane, spacing 1 (bbox 4 x 4, diagonal 4 sqrt 2). Vertex (i, j) = 5 j + i.
Eigen::MatrixXd grid() {
  Eigen::MatrixXd V(25, 3);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) V.row(5 * j + i) << i, j, 0;
  return V;
}

TEST(Scenario, FixedThenHandlesWithRigidMotion) {
  const auto V = grid();
  const auto s = iarap::parse_scenario(R"({
    "fixed": {"bottom": 0.1, "axis": "y"},
    "handles": [{"vertices": {"top": 0.1, "axis": "y"}, "translate": [0, 0, 1],
                 "rotate": {"axis": "y", "degrees": 90}}]})",
                                       "s.json");
  const auto c = iarap::resolve_scenario(s, V);
  ASSERT_EQ(c.fixed.size(), 10);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(c.fixed(k), k);
    EXPECT_EQ(c.targets.row(k), V.row(k));
  }
  // Top row rotated 90 degrees about y through its centroid (2, 4, 0), then lifted by 1 in z:
  // (x, 4, 0) -> (2, 4, -(x - 2) + 1).
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(c.fixed(5 + k), 20 + k);
    const Eigen::RowVector3d expected(2, 4, -(k - 2.0) + 1);
    EXPECT_LT((c.targets.row(5 + k) - expected).norm(), 1e-14 * 4) << k; // rounding of cos(pi/2)
  }
}

TEST(Scenario, RelativeTranslationAndExplicitCenter) {
  const auto V = grid();
  iarap::Scenario s;
  iarap::Handle h;
  iarap::Region r;
  r.indices = {24};
  h.vertices = {r};
  h.translation = Eigen::Vector3d(0.5, 0, 0); // half a diagonal
  h.translation_relative = true;
  h.rotation_axis = Eigen::Vector3d(0, 0, 5);
  h.rotation_degrees = 180;
  h.rotation_center = Eigen::Vector3d(0.5, 0.5, 0); // bbox centre (2, 2, 0)
  h.rotation_center_relative = true;
  s.handles = {h};
  const auto c = iarap::resolve_scenario(s, V);
  ASSERT_EQ(c.fixed.size(), 1);
  // (4, 4, 0) turned half a turn about z through (2, 2, 0) is (0, 0, 0); plus (2 sqrt 2, 0, 0).
  EXPECT_LT((c.targets.row(0) - Eigen::RowVector3d(0.5 * std::sqrt(32.0), 0, 0)).norm(), 1e-14 * 4);
}

// Resolving the scenario text on V must throw an InputError whose message contains fragment.
void expect_resolve_error(const std::string& text, const std::string& source, const std::string& fragment) {
  const auto scenario = iarap::parse_scenario(text, source);
  try {
    iarap::resolve_scenario(scenario, grid());
    FAIL() << "no error for " << text;
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Scenario, OverlapIsAnErrorNamingBothParts) {
  expect_resolve_error(
      R"({"fixed": {"bottom": 0.5}, "handles": [{"vertices": [3, 12], "translate": [0, 0, 1]}]})", "s.json",
      "s.json: $.handles[0]: vertex 3 is also in the fixed set");
  expect_resolve_error(R"({"handles": [{"vertices": [3]}, {"vertices": [4, 3], "translate": [1, 0, 0]}]})",
                       "t.json", "t.json: $.handles[1]: vertex 3 is also in t.json: $.handles[0]");
}

TEST(Scenario, EmptyRegionAndOutOfRangeIndexNameThePath) {
  expect_resolve_error(R"({"fixed": [{"sphere": {"center": [9, 9, 9], "radius": 1}}]})", "s.json",
                       "s.json: $.fixed[0]: selects no vertex");
  expect_resolve_error(R"({"fixed": [0, 25]})", "s.json",
                       "s.json: $.fixed: vertex index 25 out of range; the mesh has 25");
}

// Issue 32: a handle with "weight" is soft: its vertices and targets go to ConstraintSet::soft.
TEST(Scenario, WeightedHandleIsSoft) {
  const auto V = grid();
  const auto s = iarap::parse_scenario(R"({
    "fixed": {"bottom": 0.1, "axis": "y"},
    "handles": [{"vertices": {"top": 0.1, "axis": "y"}, "translate": [0, 0, 1], "weight": 0.5}]})",
                                       "s.json");
  const auto c = iarap::resolve_scenario(s, V);
  const auto hard = iarap::resolve_scenario(iarap::parse_scenario(R"({
    "fixed": {"bottom": 0.1, "axis": "y"},
    "handles": [{"vertices": {"top": 0.1, "axis": "y"}, "translate": [0, 0, 1]}]})",
                                                                  "s.json"),
                                            V);
  const Eigen::Index n = c.fixed.size();
  ASSERT_EQ(c.soft.vertices.size(), hard.fixed.size() - n);
  ASSERT_GT(c.soft.vertices.size(), 0);
  for (Eigen::Index k = 0; k < c.soft.vertices.size(); ++k) {
    EXPECT_EQ(c.soft.vertices(k), hard.fixed(n + k));
    EXPECT_EQ(c.soft.vertex_targets.row(k), hard.targets.row(n + k));
    EXPECT_EQ(c.soft.vertex_weights(k), 0.5);
  }
  for (const char* bad : {"0", "-1", "\"a\""}) {
    try {
      iarap::parse_scenario(std::string(R"({"handles": [{"vertices": [1], "weight": )") + bad + "}]}",
                            "s.json");
      ADD_FAILURE() << bad;
    } catch (const iarap::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("s.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("weight"), std::string::npos) << e.what();
    }
  }
}

TEST(Scenario, NothingConstrained) {
  iarap::Scenario s;
  s.source = "s.json";
  EXPECT_THROW(iarap::resolve_scenario(s, grid()), iarap::InputError);
}

} // namespace
