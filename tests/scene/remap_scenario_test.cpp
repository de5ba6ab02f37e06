// Scenarios carried over to a repaired mesh (issue 20, item 7), and where each constraint came from.
#include "iarap/core/errors.h"
#include "iarap/scene/read_scenario.h"
#include "iarap/scene/remap_scenario.h"
#include "iarap/scene/scenario.h"

#include <gtest/gtest.h>

using namespace iarap;

TEST(RemapScenario, IndicesFollowTheRepairAndRemovedOnesAreNamed) {
  const Scenario s =
      parse_scenario(R"({"fixed": [0, 3], "handles": [{"vertices": {"top": 0.5}}]})", "s.json");
  // Old vertex 1 removed (unreferenced), old 3 welded onto old 0, old 2 becomes 1.
  const Eigen::VectorXi old_to_new = (Eigen::VectorXi(4) << 0, -1, 1, 0).finished();
  const Scenario r = remap_scenario(s, old_to_new);
  EXPECT_EQ(r.fixed[0].indices, std::vector<int>({0})); // 0 and 3 merged into one
  EXPECT_EQ(r.handles[0].vertices[0].kind, RegionKind::Top);
  const Scenario bad = parse_scenario(R"({"fixed": [1]})", "s.json");
  try {
    remap_scenario(bad, old_to_new);
    FAIL() << "no error for a removed vertex";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: $.fixed: vertex 1 is used by no face"), std::string::npos)
        << e.what();
  }
}

TEST(RemapScenario, ConstraintsRememberTheirHandle) {
  Eigen::MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const ConstraintSet c = resolve_scenario(
      parse_scenario(R"({"fixed": [0], "handles": [{"vertices": [2], "translate": [0, 0, 1]}]})", "s.json"),
      V);
  ASSERT_EQ(c.origins.size(), 2u);
  EXPECT_EQ(c.origins[0], "s.json: $.fixed");
  EXPECT_EQ(c.origins[1], "s.json: $.handles[0]");
}

// A number beyond double (1e400) names the file and line (before: "[json.exception.out_of_range.406] number
// overflow parsing '1e400'", no file).
TEST(RemapScenario, NumberBeyondDoubleNamesTheLine) {
  try {
    parse_scenario("{\"fixed\": [0],\n\"handles\": [{\"vertices\": [1], \"translate\": [1e400, 0, 0]}]}",
                   "s.json");
    FAIL() << "no error for 1e400";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json:2: number 1e400 is beyond the range of a double"),
              std::string::npos)
        << e.what();
  }
}
