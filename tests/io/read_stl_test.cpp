#include "iarap/io/read_mesh.h"
#include "mesh_file_fixtures.h"

#include <cstdint>
#include <cstring>

using iarap::read_stl;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

namespace {

// Two triangles of the unit square sharing the diagonal (0,0,0)-(1,1,0).
const float square[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};

std::string binary_square(const std::string& header_text) {
  std::string s = header_text;
  s.resize(80, ' ');
  const auto put_u32 = [&](std::uint32_t u) {
    for (int i = 0; i < 4; ++i) s += static_cast<char>((u >> (8 * i)) & 0xff);
  };
  const auto put_float = [&](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    put_u32(u);
  };
  put_u32(2);
  for (const auto& tri : square) {
    for (int k = 0; k < 3; ++k) put_float(0.0f); // normal
    for (const auto& p : tri)
      for (float x : p) put_float(x);
    s += std::string(2, '\0');
  }
  return s;
}

void expect_welded_square(const iarap::MeshData& m) {
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2)); // numbered by first appearance
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.V.row(3), Eigen::RowVector3d(0, 1, 0));
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("welded 6 STL triangle corners into 4 vertices"), std::string::npos)
      << m.notes[0];
}

} // namespace

TEST(ReadStl, AsciiWeldsIdenticalCorners) {
  const std::string text =
      "solid square\n"
      "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n endloop\nendfacet\n"
      "facet normal 0 0 1\n outer loop\n  vertex -0 0 0\n  vertex 1 1 0\n  vertex 0 1 0\n endloop\nendfacet\n"
      "endsolid square\n";
  expect_welded_square(read_stl(write_temp_file("square.stl", text)));
}

TEST(ReadStl, BinaryEvenWhenTheHeaderSaysSolid) {
  expect_welded_square(read_stl(write_temp_file("square_bin.stl", binary_square("binary"))));
  expect_welded_square(read_stl(write_temp_file("square_solid.stl", binary_square("solid but binary"))));
}

TEST(ReadStl, ErrorsNameLineOrOffset) {
  const std::string whole = binary_square("binary");
  const std::string truncated = write_temp_file("truncated.stl", whole.substr(0, whole.size() - 10));
  expect_input_error([&] { read_stl(truncated); }, {truncated + ": byte offset 80", "declares 2 triangles"});
  const std::string bad =
      write_temp_file("bad.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 x\n");
  expect_input_error([&] { read_stl(bad); }, {":4:", "facet 0", "'x'"});
  const std::string unfinished =
      write_temp_file("unfinished.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
  expect_input_error([&] { read_stl(unfinished); }, {":4:", "endsolid"});
  const std::string two = write_temp_file(
      "two.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n");
  expect_input_error([&] { read_stl(two); }, {":6:", "facet 0 has 2 vertices"});
  const std::string tiny = write_temp_file("tiny.stl", "xyz");
  expect_input_error([&] { read_stl(tiny); }, {": byte offset 3", "too short"});
}
