#include "iarap/io/read_mesh.h"
#include "mesh_file_fixtures.h"

#include <chrono>

using iarap::read_off;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

TEST(ReadOff, HeaderVariantsCommentsColorsAndQuads) {
  const std::string path = write_temp_file("variants.off", "COFF 5 2 0\n"
                                                           "# a comment\n"
                                                           "0 0 0 255 0 0 255\n"
                                                           "1 0 0 255 0 0 255\n"
                                                           "\n"
                                                           "1 1 0 255 0 0 255\n"
                                                           "0 1 0 255 0 0 255\n"
                                                           "2 0.5 1e-3 255 0 0 255\n"
                                                           "4 0 1 2 3 0.5 0.5 0.5\n"
                                                           "3 1 4 2\n");
  const iarap::MeshData m = read_off(path);
  ASSERT_EQ(m.V.rows(), 5);
  EXPECT_EQ(m.V(4, 2), 1e-3);
  ASSERT_EQ(m.F.rows(), 3);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(1, 4, 2));
  EXPECT_EQ(m.notes.size(), 1u);
}

TEST(ReadOff, CountsOnFollowingLines) {
  const iarap::MeshData m =
      read_off(write_temp_file("split.off", "OFF\n3\n1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(m.V.rows(), 3);
  EXPECT_EQ(m.F.rows(), 1);
}

TEST(ReadOff, ErrorsNameTheLine) {
  const std::string truncated = write_temp_file("truncated.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n");
  expect_input_error([&] { read_off(truncated); }, {truncated + ":4:", "2 of 4 vertices"});
  const std::string few_faces =
      write_temp_file("few_faces.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_input_error([&] { read_off(few_faces); }, {"1 of 2 faces"});
  const std::string extra =
      write_temp_file("extra.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n");
  expect_input_error([&] { read_off(extra); }, {":7:", "unexpected data"});
  const std::string bad_token = write_temp_file("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n");
  expect_input_error([&] { read_off(bad_token); }, {":4:", "vertex 1", "'zero'"});
  const std::string short_face =
      write_temp_file("short_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n");
  expect_input_error([&] { read_off(short_face); }, {":6:", "face 0 declares 4 corners"});
  const std::string range =
      write_temp_file("range.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 3\n");
  expect_input_error([&] { read_off(range); }, {":7:", "face 1", "vertex index 3", "3 vertices"});
  const std::string negative = write_temp_file("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  expect_input_error([&] { read_off(negative); }, {":6:", "face 0", "-1"});
  const std::string not_off = write_temp_file("not.off", "PLY\n3 1 0\n");
  expect_input_error([&] { read_off(not_off); }, {":1:", "OFF"});
  const std::string bad_count = write_temp_file("bad_count.off", "OFF\n3 x 0\n");
  expect_input_error([&] { read_off(bad_count); }, {":2:", "'x'"});
}

TEST(ReadOff, HugeCountsFailWithoutAllocating) {
  // 10^12 vertices would need 24 TB; the reader must stop at the end of the data, quickly.
  const std::string path = write_temp_file("huge.off", "OFF\n1000000000000 1000000000000 0\n0 0 0\n1 0 0\n");
  const auto start = std::chrono::steady_clock::now();
  expect_input_error([&] { read_off(path); }, {":4:", "2 of 1000000000000 vertices"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}
