#include "iarap/io/read_mesh.h"
#include "mesh_file_fixtures.h"

#include <cmath>

using iarap::read_obj;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

TEST(ReadObj, CornerFormsNegativeIndicesAndPolygons) {
  const std::string path = write_temp_file("forms.obj", "# comment\n"
                                                        "mtllib x.mtl\n"
                                                        "v 0 0 0\n"
                                                        "v 1 0 0 1.0\n"
                                                        "vt 0 0\n"
                                                        "vn 0 0 1\n"
                                                        "v 1 1 0 0.5 0.5 0.5\n"
                                                        "v 0 1 0\n"
                                                        "g part\n"
                                                        "f 1/1/1 2//1 3/1\n"
                                                        "f -4 -2 -1\n"
                                                        "v 2 0.5 0\n"
                                                        "f 2 5 3 # trailing comment\n"
                                                        "f 1 2 5 3 4\n");
  const iarap::MeshData m = read_obj(path);
  ASSERT_EQ(m.V.rows(), 5);
  EXPECT_EQ(m.V(1, 0), 1.0);
  EXPECT_EQ(m.V(2, 1), 1.0); // w and colors ignored, order kept
  EXPECT_EQ(m.V(4, 1), 0.5);
  ASSERT_EQ(m.F.rows(), 6);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3)); // -4 -2 -1 with 4 vertices defined
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(1, 4, 2));
  // Pentagon fanned from its first corner.
  EXPECT_EQ(m.F.row(3), Eigen::RowVector3i(0, 1, 4));
  EXPECT_EQ(m.F.row(4), Eigen::RowVector3i(0, 4, 2));
  EXPECT_EQ(m.F.row(5), Eigen::RowVector3i(0, 2, 3));
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("triangulated 1 polygon"), std::string::npos) << m.notes[0];
}

TEST(ReadObj, NonFiniteTokensLoad) {
  const iarap::MeshData m =
      read_obj(write_temp_file("nan.obj", "v nan inf -inf\nv 1 2 3\nv 4 5 6\nf 1 2 3\n"));
  EXPECT_TRUE(std::isnan(m.V(0, 0)));
  EXPECT_TRUE(std::isinf(m.V(0, 1)));
  EXPECT_LT(m.V(0, 2), 0);
}

TEST(ReadObj, ErrorsNameTheLine) {
  const std::string bad_token = write_temp_file("bad_token.obj", "v 0 0 0\nv 1 abc 0\n");
  expect_input_error([&] { read_obj(bad_token); }, {bad_token + ":2:", "'abc'"});
  const std::string short_vertex = write_temp_file("short_vertex.obj", "v 0 0\n");
  expect_input_error([&] { read_obj(short_vertex); }, {":1:", "3 coordinates"});
  const std::string out_of_range =
      write_temp_file("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n");
  expect_input_error([&] { read_obj(out_of_range); }, {":5:", "face 1", "vertex index 9", "3 vertices"});
  const std::string zero = write_temp_file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  expect_input_error([&] { read_obj(zero); }, {":4:", "index 0"});
  const std::string relative = write_temp_file("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
  expect_input_error([&] { read_obj(relative); }, {":3:", "-3", "2 vertices"});
  const std::string bad_index = write_temp_file("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2x 3\n");
  expect_input_error([&] { read_obj(bad_index); }, {":4:", "'2x'"});
  const std::string two = write_temp_file("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expect_input_error([&] { read_obj(two); }, {":3:", "2 corners"});
  expect_input_error([] { read_obj("/nonexistent/mesh.obj"); }, {"/nonexistent/mesh.obj", "cannot open"});
}

TEST(ReadObj, BinaryGarbageIsAnError) {
  std::string garbage = "v \x01\x02\x03\xff\xfe 0 0\n";
  garbage += std::string("\0\0\x80", 3);
  const std::string path = write_temp_file("garbage.obj", garbage);
  expect_input_error([&] { read_obj(path); }, {path + ":1:", "bad vertex coordinate"});
}
