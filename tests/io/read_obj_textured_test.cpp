// read_obj_textured: the texture coordinates, corners' texture indices and face lines of an OBJ, on files
// whose answer is written out by hand, and the errors naming the line.
#include "iarap/io/read_obj_textured.h"
#include "mesh_file_fixtures.h"

using iarap::read_obj_textured;
using iarap::TexturedObj;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

TEST(ReadObjTextured, TextureIndicesPolygonsAndTheirFans) {
  const std::string path = write_temp_file("textured.obj", "v 0 0 0\n"
                                                           "v 1 0 0\n"
                                                           "v 1 1 0\n"
                                                           "v 0 1 0\n"
                                                           "v 2 0.5 0\n"
                                                           "vt 0 0\n"
                                                           "vt 1 0 0.5\n"
                                                           "vt 1 1\n"
                                                           "vt 0.25\n"
                                                           "f 1/1 2/2 3/3 4/4\n"
                                                           "f 2/2/1 5/-1/1 3/3/1\n"
                                                           "f 1 2 4\n");
  const TexturedObj obj = read_obj_textured(path);
  // The mesh is read_obj's.
  EXPECT_EQ(obj.mesh.V, iarap::read_obj(path).V);
  EXPECT_EQ(obj.mesh.F, iarap::read_obj(path).F);
  ASSERT_EQ(obj.TC.rows(), 4);
  EXPECT_EQ(obj.TC.row(1), Eigen::RowVector2d(1, 0));    // w dropped
  EXPECT_EQ(obj.TC.row(3), Eigen::RowVector2d(0.25, 0)); // v missing: 0
  // The quad's fan (1 2 3), (1 3 4) takes its corners' indices; -1 is the last vt so far (4th).
  ASSERT_EQ(obj.FT.rows(), 4);
  EXPECT_EQ(obj.FT.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(obj.FT.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(obj.FT.row(2), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(obj.FT.row(3), Eigen::RowVector3i(-1, -1, -1)); // a face without texture indices
  EXPECT_EQ(obj.polygon_of_triangle, (std::vector<int>{0, 0, 1, 2}));
  ASSERT_EQ(obj.polygons.size(), 3);
  EXPECT_EQ(obj.polygons.first, (std::vector<int>{0, 4, 7, 10}));
  EXPECT_EQ(obj.polygons.corners(0), 4);
  EXPECT_EQ(obj.polygons.vertex, (std::vector<int>{0, 1, 2, 3, 1, 4, 2, 0, 1, 3}));
  EXPECT_EQ(obj.polygons.texture, (std::vector<int>{0, 1, 2, 3, 1, 3, 2, -1, -1, -1}));
}

TEST(ReadObjTextured, BadTextureReferencesNameTheLine) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n";
  const std::string missing = write_temp_file("vt_missing.obj", head + "f 1/1 2/2 3/3\nf 1/1 2/2 3/9\n");
  expect_input_error([&] { read_obj_textured(missing); },
                     {missing + ":7:", "face 1", "texture index 9", "2 texture coordinates"});
  const std::string zero = write_temp_file("vt_zero.obj", head + "f 1/0 2/1 3/2\n");
  expect_input_error([&] { read_obj_textured(zero); }, {":6:", "texture index 0"});
  const std::string relative = write_temp_file("vt_relative.obj", head + "f 1/-3 2/1 3/2\n");
  expect_input_error([&] { read_obj_textured(relative); }, {":6:", "relative texture index -3", "2 texture"});
  const std::string bad = write_temp_file("vt_bad.obj", head + "f 1/1 2/x 3/2\n");
  expect_input_error([&] { read_obj_textured(bad); }, {":6:", "bad texture index", "'2/x'"});
  const std::string some = write_temp_file("vt_some.obj", head + "f 1/1 2 3/2\n");
  expect_input_error([&] { read_obj_textured(some); }, {":6:", "some corners only"});
  const std::string number = write_temp_file("vt_number.obj", "v 0 0 0\nvt 0 abc\n");
  expect_input_error([&] { read_obj_textured(number); }, {":2:", "bad texture coordinate", "'abc'"});
  // read_obj ignores vt lines and texture indices, as before.
  EXPECT_EQ(iarap::read_obj(missing).F.rows(), 2);
}
