#include "iarap/io/read_mesh.h"
#include "mesh_file_fixtures.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>

using iarap::read_ply;
using iarap::test::expect_input_error;
using iarap::test::write_temp_file;

namespace {

// Appends a value in the requested byte order, independent of the host's.
template <typename T> void put(std::string& out, T value, bool big_endian) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  const bool host_little = first == 1;
  if (host_little == big_endian)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

// A binary PLY with float vertices plus an extra property, an ignored `edge` element, a quad face with
// ushort count and uint indices, and a triangle.
std::string binary_ply(bool big_endian) {
  std::string s =
      std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
      " 1.0\ncomment test\nelement vertex 5\nproperty float x\nproperty uchar red\nproperty double y\n"
      "property float z\nelement edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "element face 2\nproperty int flags\nproperty list ushort uint vertex_indices\nend_header\n";
  const double xyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0.1, 0.25}};
  for (const auto& p : xyz) {
    put(s, static_cast<float>(p[0]), big_endian);
    put(s, static_cast<std::uint8_t>(200), big_endian);
    put(s, p[1], big_endian);
    put(s, static_cast<float>(p[2]), big_endian);
  }
  put(s, std::int32_t{0}, big_endian);
  put(s, std::int32_t{1}, big_endian);
  put(s, std::int32_t{7}, big_endian);
  put(s, std::uint16_t{4}, big_endian);
  for (std::uint32_t i : {0u, 1u, 2u, 3u}) put(s, i, big_endian);
  put(s, std::int32_t{7}, big_endian);
  put(s, std::uint16_t{3}, big_endian);
  for (std::uint32_t i : {1u, 4u, 2u}) put(s, i, big_endian);
  return s;
}

void expect_binary_mesh(const iarap::MeshData& m) {
  ASSERT_EQ(m.V.rows(), 5);
  EXPECT_EQ(m.V(4, 0), 2.0);
  EXPECT_EQ(m.V(4, 1), 0.1); // stored as double: exact
  EXPECT_EQ(m.V(4, 2), 0.25);
  ASSERT_EQ(m.F.rows(), 3);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(1, 4, 2));
}

const char* ascii_header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                           "property double z\nproperty float nx\n";

} // namespace

TEST(ReadPly, BinaryBothEndiannesses) {
  expect_binary_mesh(read_ply(write_temp_file("little.ply", binary_ply(false))));
  expect_binary_mesh(read_ply(write_temp_file("big.ply", binary_ply(true))));
}

TEST(ReadPly, AsciiWithExtraPropertiesAndListTypes) {
  const std::string text =
      std::string(ascii_header) +
      "element face 2\nproperty list uchar int vertex_index\nproperty uchar red\nend_header\n"
      "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n3 0 1 2 9\n3 0 2 3 9\n";
  const iarap::MeshData m = read_ply(write_temp_file("ascii.ply", text));
  ASSERT_EQ(m.V.rows(), 4);
  ASSERT_EQ(m.F.rows(), 2);
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_TRUE(m.notes.empty());
}

TEST(ReadPly, TriangleStripsRestartAlternateAndSkipDegenerate) {
  // Run 0 1 2 3 gives (0,1,2) and, reversed to keep the orientation, the odd (2,1,3). After the -1 restart
  // the run 4 5 5 6 7 gives (4,5,5) and (5,5,6), skipped as degenerate, then (5,6,7) as triangle 2 (even).
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
      "10 0 1 2 3 -1 4 5 5 6 7\n";
  const iarap::MeshData m = read_ply(write_temp_file("strips.ply", text));
  ASSERT_EQ(m.F.rows(), 3);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(m.F.row(1), Eigen::RowVector3i(2, 1, 3));
  EXPECT_EQ(m.F.row(2), Eigen::RowVector3i(5, 6, 7));
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("skipping 2 degenerate"), std::string::npos) << m.notes[0];
}

TEST(ReadPly, AsciiErrorsNameTheLine) {
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string truncated = write_temp_file("truncated.ply", ascii_header + faces + "0 0 0 1\n1 0 0 1\n");
  expect_input_error([&] { read_ply(truncated); }, {truncated + ":12:", "2 of 4 vertex records"});
  const std::string bad =
      write_temp_file("bad.ply", ascii_header + faces + "0 0 0 1\n1 0 0 1\n1 one 0 1\n0 1 0 1\n3 0 1 2\n");
  expect_input_error([&] { read_ply(bad); }, {":13:", "vertex 2", "'one'", "property y"});
  const std::string range =
      write_temp_file("range.ply", ascii_header + faces + "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n3 0 1 4\n");
  expect_input_error([&] { read_ply(range); }, {":15:", "face 0", "vertex index 4", "4 vertices"});
  const std::string short_list = write_temp_file(
      "short_list.ply", ascii_header + faces + "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n4 0 1 2\n");
  expect_input_error([&] { read_ply(short_list); }, {":15:", "declares 4 items"});
  const std::string extra = write_temp_file("extra.ply", ascii_header + faces + "0 0 0 1 5\n");
  expect_input_error([&] { read_ply(extra); }, {":11:", "1 values more"});
  const std::string no_xyz = write_temp_file(
      "no_xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n");
  expect_input_error([&] { read_ply(no_xyz); }, {":3:", "x, y, z"});
  const std::string bad_format =
      write_temp_file("bad_format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n");
  expect_input_error([&] { read_ply(bad_format); }, {":2:", "binary_middle_endian"});
}

TEST(ReadPly, BinaryErrorsNameTheByteOffset) {
  const std::string whole = binary_ply(false);
  const std::string truncated = write_temp_file("truncated_bin.ply", whole.substr(0, whole.size() - 5));
  expect_input_error([&] { read_ply(truncated); },
                     {truncated + ": byte offset", "file ends inside face record 1"});
  const std::string trailing = write_temp_file("trailing_bin.ply", whole + "xx");
  expect_input_error([&] { read_ply(trailing); },
                     {": byte offset " + std::to_string(whole.size()), "2 bytes after"});
  // Out-of-range index in the last face: 4 -> 40.
  std::string range = whole;
  range[range.size() - 8] = 40;
  const std::string range_path = write_temp_file("range_bin.ply", range);
  expect_input_error([&] { read_ply(range_path); }, {": byte offset", "face 1", "vertex index 40"});
  // Header promising 10^12 vertices over a few bytes: rejected before any allocation.
  std::string huge = whole;
  huge.replace(huge.find("vertex 5"), 8, "vertex 1000000000000");
  const std::size_t huge_header = huge.find("end_header\n") + 11;
  const std::string huge_path = write_temp_file("huge_bin.ply", huge);
  const auto start = std::chrono::steady_clock::now();
  expect_input_error([&] { read_ply(huge_path); },
                     {": byte offset " + std::to_string(huge_header) + ":", "1000000000000 vertex records"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST(ReadPly, GarbageIsAnError) {
  const std::string garbage = write_temp_file("garbage.ply", std::string("\x7f"
                                                                         "ELF\x02\x01\x01\0\0\0",
                                                                         10));
  expect_input_error([&] { read_ply(garbage); }, {garbage + ":1:", "not a PLY file"});
  const std::string no_end = write_temp_file("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 0\n");
  expect_input_error([&] { read_ply(no_end); }, {":3:", "end_header"});
}

TEST(ReadPly, AsciiHugeCountAndFacesBeforeVertices) {
  const std::string huge =
      write_temp_file("huge_ascii.ply", "ply\nformat ascii 1.0\nelement vertex 1000000000000\n"
                                        "property float x\nproperty float y\nproperty float z\n"
                                        "end_header\n0 0 0\n1 0 0\n");
  const auto start = std::chrono::steady_clock::now();
  expect_input_error([&] { read_ply(huge); }, {huge + ":9:", "2 of 1000000000000 vertex records"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  // Faces may come first; their indices are checked once the vertex count is known.
  const std::string first =
      write_temp_file("faces_first.PLY", "ply\nformat ascii 1.0\nelement face 1\n"
                                         "property list uchar int vertex_indices\n"
                                         "element vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nend_header\n3 2 1 0\n"
                                         "0 0 0\n1 0 0\nnan inf 0\n");
  const iarap::MeshData m = iarap::read_mesh(first);
  EXPECT_EQ(m.F.row(0), Eigen::RowVector3i(2, 1, 0));
  EXPECT_TRUE(std::isnan(m.V(2, 0)));
  EXPECT_TRUE(std::isinf(m.V(2, 1)));
}
