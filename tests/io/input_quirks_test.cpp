// Issue 20, item 6: inputs other tools write. A UTF-8 byte-order mark (Windows editors) made OBJ lose its
// first vertex silently and gave misleading errors in the other formats; OFF face records spanning lines
// (valid OFF) were rejected; a folder given as a mesh failed with "basic_string::_M_create".
#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "mesh_file_fixtures.h"

#include <gtest/gtest.h>

using namespace iarap;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

namespace {
const std::string bom = "\xEF\xBB\xBF";
} // namespace

TEST(InputQuirks, ByteOrderMarkIsSkippedInEveryTextFormat) {
  const MeshData obj = read_obj(write_temp_file("bom.obj", bom + "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(obj.V.rows(), 3);
  EXPECT_EQ(obj.F.rows(), 1);
  const MeshData off =
      read_off(write_temp_file("bom.off", bom + "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(off.F.rows(), 1);
  const MeshData ply = read_ply(write_temp_file(
      "bom.ply",
      bom + "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 "
            "2\n"));
  EXPECT_EQ(ply.F.rows(), 1);
  const MeshData stl = read_stl(write_temp_file(
      "bom.stl",
      bom + "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
            "endfacet\nendsolid t\n"));
  EXPECT_EQ(stl.V.rows(), 3);
  EXPECT_EQ(stl.F.rows(), 1);
}

TEST(InputQuirks, OffFaceRecordsMaySpanLines) {
  const MeshData m = read_off(write_temp_file("multiline.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                                                               "3\n0 1\n2\n3 0 2 3 0.5 0.5 0.5\n"));
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  // A record cut short by the end of the file names its face and the line it starts on.
  expect_input_error(
      [] { read_off(write_temp_file("cut.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0\n1\n")); },
      {"cut.off:6:", "face 0 declares 3 corners but the file ends after 2"});
}

TEST(InputQuirks, FolderGivenAsMeshIsNamed) {
  const auto dir = iarap::test::temp_dir("folder_mesh") / "mesh.obj";
  std::filesystem::create_directories(dir);
  expect_input_error([&] { read_mesh(dir.string()); }, {dir.string(), "is a folder, not a mesh file"});
}
