// write_uv_map: the OBJ reads back with its vertices and faces, the vt lines hold UV exactly, and the
// text form has one line per vertex.
#include "iarap/param/write_uv_map.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "param/disk_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace iarap {
namespace {

// The numbers after `prefix` on each line that starts with it.
std::vector<std::vector<double>> lines_with(const std::filesystem::path& path, const std::string& prefix) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream fields(line.substr(prefix.size()));
    std::vector<double> row;
    for (double x; fields >> x;) row.push_back(x);
    rows.push_back(row);
  }
  return rows;
}

TEST(WriteUvMap, ObjHoldsTheMeshAndOneTextureCoordinatePerVertex) {
  const auto dir = test::temp_dir("uv_map");
  const test::TestMesh mesh = test::flat_disk(2, 7);
  Eigen::MatrixXd UV = mesh.V.leftCols(2) * (1.0 / 3.0); // digits that need all 17 to round-trip
  write_uv_map((dir / "map.obj").string(), mesh.V, mesh.F, UV);
  const MeshData back = read_obj((dir / "map.obj").string());
  EXPECT_EQ(back.V, mesh.V);
  EXPECT_EQ(back.F, mesh.F);
  const auto vt = lines_with(dir / "map.obj", "vt ");
  ASSERT_EQ(vt.size(), static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < UV.rows(); ++v) {
    EXPECT_EQ(vt[static_cast<std::size_t>(v)][0], UV(v, 0));
    EXPECT_EQ(vt[static_cast<std::size_t>(v)][1], UV(v, 1));
  }
  // Faces name the texture coordinate of each corner: f a/a b/b c/c.
  std::ifstream in(dir / "map.obj");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nf 1/1 2/2 3/3\n"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(WriteUvMap, TextHasOneUvLinePerVertex) {
  const auto dir = test::temp_dir("uv_text");
  const test::TestMesh mesh = test::flat_square(2);
  write_uv_map((dir / "map.TXT").string(), mesh.V, mesh.F, mesh.V.leftCols(2));
  const auto rows = lines_with(dir / "map.TXT", "");
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(rows[5], (std::vector<double>{1.0, 0.5}));
  std::filesystem::remove_all(dir);
}

TEST(WriteUvMap, RefusesOtherExtensionsAndWrongShapes) {
  const auto dir = test::temp_dir("uv_bad");
  const test::TestMesh mesh = test::flat_square(1);
  EXPECT_THROW(write_uv_map((dir / "map.ply").string(), mesh.V, mesh.F, mesh.V.leftCols(2)), InputError);
  EXPECT_THROW(write_uv_map((dir / "map.obj").string(), mesh.V, mesh.F, mesh.V), InputError);
  EXPECT_THROW(write_uv_map((dir / "no/such/map.obj").string(), mesh.V, mesh.F, mesh.V.leftCols(2)),
               InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "map.obj"));
  std::filesystem::remove_all(dir);
}

TEST(WriteUvAtlas, OneTextureCoordinatePerDistinctVertexUvInOrderOfFirstUse) {
  // Two triangles on the square's diagonal (0, 2): vertex 0 keeps one UV in both, vertex 2 has one per
  // triangle (a seam), vertex 0's second corner writes its u as -0.0, which is the same UV (== equal).
  const auto dir = test::temp_dir("uv_atlas_vt");
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  Eigen::MatrixXd corner_uv(6, 2);
  corner_uv << 0.0, 0.0, 0.5, 0.0, 0.5, 0.5, //
      -0.0, 0.0, 0.75, 0.5, 0.25, 0.5;
  const auto path = dir / "atlas.obj";
  write_uv_atlas(path.string(), V, F, corner_uv);
  const std::vector<std::vector<double>> vt = lines_with(path, "vt ");
  const std::vector<std::vector<double>> expected{{0, 0}, {0.5, 0}, {0.5, 0.5}, {0.75, 0.5}, {0.25, 0.5}};
  EXPECT_EQ(vt, expected);
  std::ifstream in(path);
  std::vector<std::string> faces;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("f ", 0) == 0) faces.push_back(line);
  EXPECT_EQ(faces, (std::vector<std::string>{"f 1/1 2/2 3/3", "f 1/1 3/4 4/5"}));
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace iarap
