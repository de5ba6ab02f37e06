// iarap::version() is the VERSION file's first line, the one source of the version.
#include "iarap/core/version.h"

#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <string>

namespace iarap {
namespace {

TEST(Version, IsTheVersionFile) {
  std::ifstream file(std::string(IARAP_SOURCE_DIR) + "/VERSION");
  std::string expected;
  ASSERT_TRUE(std::getline(file, expected));
  EXPECT_EQ(version(), expected);
  EXPECT_TRUE(std::regex_match(version(), std::regex(R"(\d+\.\d+\.\d+)"))) << version();
}

} // namespace
} // namespace iarap
