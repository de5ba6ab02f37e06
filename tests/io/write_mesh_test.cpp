#include "iarap/io/read_mesh.h"
#include "iarap/io/write_mesh.h"
#include "mesh_file_fixtures.h"

#include <cmath>
#include <filesystem>
#include <random>

using iarap::test::expect_input_error;
using iarap::test::temp_dir;

namespace {

// Coordinates across many magnitudes, signs and awkward binary fractions, so only exact printing round-trips.
Eigen::MatrixXd awkward_positions(int n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  Eigen::MatrixXd V(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) V(i, k) = std::ldexp(mantissa(rng), exponent(rng) / 10) * (1.0 + 1.0 / 3.0);
  V(0, 0) = 0.1;
  V(0, 1) = -0.0;
  V(0, 2) = 5e-324; // smallest subnormal
  return V;
}

Eigen::MatrixXi some_faces(int n_vertices, int n_faces) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> index(0, n_vertices - 1);
  Eigen::MatrixXi F(n_faces, 3);
  for (int f = 0; f < n_faces; ++f) F.row(f) << index(rng), index(rng), index(rng);
  return F;
}

void expect_round_trip(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                       void (*write)(const std::string&, const Eigen::MatrixXd&, const Eigen::MatrixXi&)) {
  write(path, V, F);
  const iarap::MeshData m = iarap::read_mesh(path);
  ASSERT_EQ(m.V.rows(), V.rows()) << path;
  ASSERT_EQ(m.F.rows(), F.rows()) << path;
  // %.17g and raw doubles are exact, so identical bits are expected (well within 1e-15 relative).
  for (Eigen::Index i = 0; i < V.size(); ++i) EXPECT_EQ(m.V.data()[i], V.data()[i]) << path << " entry " << i;
  EXPECT_EQ(m.F, F) << path;
  EXPECT_TRUE(m.notes.empty());
}

void write_binary_ply(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  iarap::write_ply(path, V, F, iarap::PlyEncoding::binary_little_endian);
}

} // namespace

TEST(WriteMesh, EveryFormatRoundTripsExactly) {
  const Eigen::MatrixXd V = awkward_positions(200);
  const Eigen::MatrixXi F = some_faces(200, 300);
  const auto dir = temp_dir("write");
  expect_round_trip((dir / "m.obj").string(), V, F, iarap::write_obj);
  expect_round_trip((dir / "m.off").string(), V, F, iarap::write_off);
  expect_round_trip((dir / "m.ply").string(), V, F,
                    [](const std::string& p, const Eigen::MatrixXd& v, const Eigen::MatrixXi& f) {
                      iarap::write_ply(p, v, f);
                    });
  expect_round_trip((dir / "b.ply").string(), V, F, write_binary_ply);
  expect_round_trip((dir / "M.OBJ").string(), V, F, iarap::write_mesh);
}

TEST(WriteMesh, BundledBunnyRoundTrips) {
  const iarap::MeshData bunny = iarap::read_mesh(iarap::test::data_path("bunny.off"));
  const auto dir = temp_dir("write_bunny");
  for (const char* name : {"bunny.obj", "bunny.off", "bunny.ply"}) {
    const std::string path = (dir / name).string();
    iarap::write_mesh(path, bunny.V, bunny.F);
    const iarap::MeshData back = iarap::read_mesh(path);
    EXPECT_EQ(back.V, bunny.V) << name;
    EXPECT_EQ(back.F, bunny.F) << name;
  }
}

TEST(WriteMesh, AtomicAndChecked) {
  const auto dir = temp_dir("write_atomic");
  const std::string path = (dir / "tri.off").string();
  Eigen::MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixXi F(1, 3);
  F << 0, 1, 2;
  iarap::write_mesh(path, V, F);
  // A bad face must throw before anything replaces the existing file, and leave no temporary behind.
  Eigen::MatrixXi bad(2, 3);
  bad << 0, 1, 2, 0, 1, 3;
  expect_input_error([&] { iarap::write_off(path, V, bad); }, {path, "face 1", "vertex 3"});
  EXPECT_EQ(iarap::read_off(path).F.rows(), 1);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "tri.off");
  }
  EXPECT_EQ(files, 1);
  expect_input_error([&] { iarap::write_mesh((dir / "tri.stl").string(), V, F); },
                     {"tri.stl", "unsupported"});
  expect_input_error([&] { iarap::write_obj("/nonexistent_dir/x.obj", V, F); }, {"/nonexistent_dir/x.obj"});
  expect_input_error([&] { iarap::read_mesh((dir / "tri.3ds").string()); }, {"tri.3ds", "unsupported"});
}
