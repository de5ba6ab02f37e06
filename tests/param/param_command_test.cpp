// End-to-end tests of `iarap param`: a disk written in code goes in, an OBJ with texture coordinates and a
// JSON report come out; the errors a user meets exit 1 (runtime) or 2 (usage) and say what is wrong.
#include "app/cli_runner.h"
#include "iarap/io/read_mesh.h"
#include "iarap/io/read_obj_textured.h"
#include "iarap/io/write_mesh.h"
#include "io/png_reader.h"
#include "mesh/small_meshes.h"
#include "param/disk_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace {

using namespace iarap::test::cli;
namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {
  return "'" + path.string() + "'";
}

TEST(ParamCommand, WritesTextureCoordinatesAndReport) {
  const auto dir = iarap::test::temp_dir("param_cli");
  const iarap::test::TestMesh cap = iarap::test::spherical_cap(8, 24, 0.9 * M_PI);
  iarap::write_mesh((dir / "cap.off").string(), cap.V, cap.F);
  const CliRun run = iarap_cli("param " + quoted(dir / "cap.off") + " --out " + quoted(dir / "uv.obj") +
                               " --json --quiet --report " + quoted(dir / "report.json"));
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j["flipped"], 0);
  EXPECT_GT(j["min_det_J"].get<double>(), 0);
  EXPECT_EQ(j["init"], "lscm");
  EXPECT_EQ(j["energies"].size(), j["iterations"].get<std::size_t>());
  EXPECT_LE(j["scaled_energy"].get<double>(), j["energy"].get<double>() * (1 + 1e-12));
  for (const char* key : {"area_distortion", "angle_distortion"})
    EXPECT_LE(j[key]["min"].get<double>(), j[key]["max"].get<double>()) << key;
  EXPECT_EQ(nlohmann::json::parse(read_file(dir / "report.json")), j);
  // The OBJ: the input's vertices and faces, one vt per vertex.
  const iarap::MeshData back = iarap::read_obj((dir / "uv.obj").string());
  EXPECT_EQ(back.F, cap.F);
  EXPECT_LT((back.V - cap.V).cwiseAbs().maxCoeff(), 1e-15);
  const std::string text = read_file(dir / "uv.obj");
  std::size_t vt = 0;
  for (std::size_t at = text.find("\nvt "); at != std::string::npos; at = text.find("\nvt ", at + 1)) ++vt;
  EXPECT_EQ(vt, static_cast<std::size_t>(cap.V.rows()));
  // With --allow-flips the same mesh folds over (arap_parameterize_test has the library's side).
  const CliRun plain = iarap_cli("param " + quoted(dir / "cap.off") + " --out " + quoted(dir / "uv.txt") +
                                 " --allow-flips --json --quiet");
  ASSERT_EQ(plain.code, 0) << plain.out;
  EXPECT_GT(parse_json(plain)["flipped"].get<int>(), 0);
  fs::remove_all(dir);
}

// The engine's options reach param: every accelerator flip-free, the gradient rule and its stop reason.
TEST(ParamCommand, EngineOptions) {
  const auto dir = iarap::test::temp_dir("param_cli_engine");
  const iarap::test::TestMesh cap = iarap::test::spherical_cap(8, 24, 0.9 * M_PI);
  iarap::write_mesh((dir / "cap.off").string(), cap.V, cap.F);
  for (const char* accel : {"none", "anderson", "lbfgs", "newton"}) {
    const CliRun run = iarap_cli("param " + quoted(dir / "cap.off") + " --out " + quoted(dir / "uv.txt") +
                                 " --accel " + accel + " --window 6 --tolerance 0 --grad-tol 1e-5 " +
                                 "--iterations 5000 --time-budget 600000 --json --quiet");
    ASSERT_EQ(run.code, 0) << run.out;
    const nlohmann::json j = parse_json(run);
    EXPECT_EQ(j["accelerator"], accel);
    EXPECT_EQ(j["stop_reason"], "gradient_tolerance") << accel;
    EXPECT_LE(j["gradient_norms"].back().get<double>(), 1e-5 * j["initial_gradient_norm"].get<double>());
    EXPECT_EQ(j["flipped"], 0) << accel;
  }
  fs::remove_all(dir);
}

TEST(ParamCommand, PictureOfTheMap) {
  const auto dir = iarap::test::temp_dir("param_cli_picture");
  const iarap::test::TestMesh cap = iarap::test::spherical_cap(5, 16, 0.5 * M_PI);
  iarap::write_mesh((dir / "cap.off").string(), cap.V, cap.F);
  const CliRun run = iarap_cli("param " + quoted(dir / "cap.off") + " --out " + quoted(dir / "uv.obj") +
                               " --picture " + quoted(dir / "uv.png") + " --json --quiet");
  ASSERT_EQ(run.code, 0) << run.out;
  EXPECT_EQ(parse_json(run)["picture"], (dir / "uv.png").string());
  const iarap::RgbImage image = iarap::test::read_png_rgb((dir / "uv.png").string());
  EXPECT_EQ(image.width, 1600);
  EXPECT_EQ(image.height, 800);
  fs::remove_all(dir);
}

TEST(ParamCommand, MeshThatIsNotADiskSaysWhatItHas) {
  const auto dir = iarap::test::temp_dir("param_cli_closed");
  const auto octahedron = iarap::test::octahedron();
  iarap::write_mesh((dir / "closed.off").string(), octahedron.V, octahedron.F);
  const CliRun run = iarap_cli(
      "param " + quoted(dir / "closed.off") + " --out " + quoted(dir / "uv.obj") + " --charts one", true);
  EXPECT_EQ(run.code, 1) << run.out;
  EXPECT_NE(run.out.find("closed.off: the mesh is not a topological disk"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("0 boundary loops"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("cut it into disks first"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(dir / "uv.obj"));
  fs::remove_all(dir);
}

// Without --charts one, a closed mesh becomes an atlas: the OBJ keeps the vertices and the faces in order,
// with a vt per (vertex, chart) and every uv in [0, 1]^2; the report lists the charts.
TEST(ParamCommand, AtlasOfAClosedMesh) {
  const auto dir = iarap::test::temp_dir("param_cli_atlas");
  const iarap::test::TestMesh torus = iarap::test::torus(24, 12);
  iarap::write_mesh((dir / "torus.off").string(), torus.V, torus.F);
  const CliRun run = iarap_cli("param " + quoted(dir / "torus.off") + " --out " + quoted(dir / "uv.obj") +
                               " --json --quiet --texture-size 512 --picture " + quoted(dir / "uv.png"));
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j["charts_mode"], "auto");
  EXPECT_GE(j["charts"].get<int>(), 2);
  EXPECT_EQ(j["chart_list"].size(), j["charts"].get<std::size_t>());
  EXPECT_EQ(j["flipped"], 0);
  EXPECT_LE(j["overlap_ratio"].get<double>(), 1e-4);
  EXPECT_EQ(j["texture_size"], 512);
  EXPECT_GT(j["seam_length"].get<double>(), 0.0);
  const iarap::MeshData back = iarap::read_obj((dir / "uv.obj").string());
  EXPECT_EQ(back.V, torus.V);
  EXPECT_EQ(back.F, torus.F);
  std::ifstream in(dir / "uv.obj");
  int vt = 0;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("vt ", 0) == 0) {
      ++vt;
      std::istringstream fields(line.substr(3));
      double u = -1, v = -1;
      fields >> u >> v;
      EXPECT_TRUE(u >= 0 && u <= 1 && v >= 0 && v <= 1) << line;
    }
  // Seam vertices have one vt per chart: more than the vertices, fewer than the corners.
  EXPECT_GT(vt, torus.V.rows());
  EXPECT_LT(vt, 3 * torus.F.rows());
  EXPECT_TRUE(fs::exists(dir / "uv.png"));
  // .txt: one 'u v' line per corner.
  ASSERT_EQ(
      iarap_cli("param " + quoted(dir / "torus.off") + " --out " + quoted(dir / "uv.txt") + " --quiet").code,
      0);
  std::ifstream text(dir / "uv.txt");
  Eigen::Index lines = 0;
  for (std::string line; std::getline(text, line);) ++lines;
  EXPECT_EQ(lines, 3 * torus.F.rows());
  // Pins are one chart's.
  std::ofstream(dir / "pins.txt") << "0 0 0\n";
  const CliRun pinned = iarap_cli("param " + quoted(dir / "torus.off") + " --out " + quoted(dir / "uv2.obj") +
                                      " --pins " + quoted(dir / "pins.txt"),
                                  true);
  EXPECT_EQ(pinned.code, 2) << pinned.out;
  EXPECT_NE(pinned.out.find("--pins needs one chart"), std::string::npos) << pinned.out;
  fs::remove_all(dir);
}

// An OBJ of quads: the output has the same quads in the same order, a vt per corner; read back with
// --charts keep, its vt seams give the same charts, each flattened from the file's layout.
TEST(ParamCommand, QuadsKeptAndChartsKept) {
  const auto dir = iarap::test::temp_dir("param_cli_quads");
  const iarap::test::TestMesh torus = iarap::test::torus(24, 12); // quad q = faces 2 q, 2 q + 1
  std::ofstream obj(dir / "quads.obj");
  for (Eigen::Index v = 0; v < torus.V.rows(); ++v)
    obj << "v " << torus.V(v, 0) << ' ' << torus.V(v, 1) << ' ' << torus.V(v, 2) << '\n';
  for (Eigen::Index q = 0; q < torus.F.rows() / 2; ++q) // (a, b, d) and (a, d, c): the quad a b d c
    obj << "f " << torus.F(2 * q, 0) + 1 << ' ' << torus.F(2 * q, 1) + 1 << ' ' << torus.F(2 * q, 2) + 1
        << ' ' << torus.F(2 * q + 1, 2) + 1 << '\n';
  obj.close();
  const CliRun run = iarap_cli("param " + quoted(dir / "quads.obj") + " --out " + quoted(dir / "uv.obj") +
                               " --json --quiet");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j["flipped"], 0);
  const iarap::TexturedObj in = iarap::read_obj_textured((dir / "quads.obj").string());
  const iarap::TexturedObj out = iarap::read_obj_textured((dir / "uv.obj").string());
  EXPECT_EQ(out.mesh.V.rows(), in.mesh.V.rows());
  EXPECT_EQ(out.polygons.first, in.polygons.first); // 4 corners each, in order
  EXPECT_EQ(out.polygons.vertex, in.polygons.vertex);
  for (int t : out.polygons.texture) EXPECT_GE(t, 0);
  EXPECT_GE(out.TC.minCoeff(), 0.0);
  EXPECT_LE(out.TC.maxCoeff(), 1.0);

  const CliRun kept = iarap_cli("param " + quoted(dir / "uv.obj") + " --out " + quoted(dir / "kept.obj") +
                                " --charts keep --json --quiet");
  ASSERT_EQ(kept.code, 0) << kept.out;
  const nlohmann::json k = parse_json(kept);
  EXPECT_EQ(k["charts_mode"], "keep");
  EXPECT_EQ(k["charts"], j["charts"]);
  EXPECT_EQ(k["flipped"], 0);
  for (const nlohmann::json& chart : k["chart_list"]) EXPECT_EQ(chart["started_from_input"], 1);

  // keep needs vt, on every face, in an OBJ.
  const CliRun no_vt = iarap_cli(
      "param " + quoted(dir / "quads.obj") + " --out " + quoted(dir / "x.obj") + " --charts keep", true);
  EXPECT_EQ(no_vt.code, 1);
  EXPECT_NE(no_vt.out.find("has no vt lines"), std::string::npos) << no_vt.out;
  std::ofstream(dir / "some.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n";
  const CliRun some = iarap_cli(
      "param " + quoted(dir / "some.obj") + " --out " + quoted(dir / "x.obj") + " --charts keep", true);
  EXPECT_EQ(some.code, 1);
  EXPECT_NE(some.out.find("face 1 (the file's f line number 2) has none"), std::string::npos) << some.out;
  iarap::write_mesh((dir / "torus.off").string(), torus.V, torus.F);
  const CliRun off = iarap_cli(
      "param " + quoted(dir / "torus.off") + " --out " + quoted(dir / "x.obj") + " --charts keep", true);
  EXPECT_EQ(off.code, 1);
  EXPECT_NE(off.out.find("not an OBJ"), std::string::npos) << off.out;
  fs::remove_all(dir);
}

TEST(ParamCommand, UsageErrors) {
  const auto dir = iarap::test::temp_dir("param_cli_usage");
  const iarap::test::TestMesh disk = iarap::test::flat_disk(2, 8);
  iarap::write_mesh((dir / "disk.obj").string(), disk.V, disk.F);
  const std::string before = read_file(dir / "disk.obj");
  const std::string mesh = "param " + quoted(dir / "disk.obj");
  const std::string out = " --out " + quoted(dir / "uv.obj");
  const struct {
    std::string args, says;
  } cases[] = {
      {mesh + " --out " + quoted(dir / "disk.obj"), "refusing to overwrite"},
      {mesh + " --out " + quoted(dir / "uv.ply"), ".obj (mesh with vt) or .txt"},
      {mesh + out + " --energy spokes-rims", "--energy"},
      {mesh + out + " --init spectral", "spectral"},
      {mesh + out + " --boundary circle --init lscm", "--init tutte or harmonic"},
      {mesh + out + " --iterations -3", "iterations"},
      {mesh + out + " --picture " + quoted(dir / "uv.jpg"), "the picture is written as .png"},
      {mesh + out + " --picture " + quoted(dir / "disk.obj"), "is the input mesh, the output or the report"},
      {mesh + out + " --tolerance nan", "finite"},
      {mesh + out + " --accel adam", "--accel"},
      {mesh + out + " --grad-tol -1", "--grad-tol"},
      {mesh + out + " --time-budget nan", "--time-budget"},
      {mesh + out + " --window -1", "--window"},
      {mesh, "--out"},
  };
  for (const auto& c : cases) {
    const CliRun run = iarap_cli(c.args, true);
    EXPECT_EQ(run.code, 2) << c.args << "\n" << run.out;
    EXPECT_NE(run.out.find(c.says), std::string::npos) << c.args << "\n" << run.out;
  }
  EXPECT_EQ(read_file(dir / "disk.obj"), before);
  EXPECT_FALSE(fs::exists(dir / "uv.obj"));
  fs::remove_all(dir);
}

TEST(ParamCommand, PinsFromAFile) {
  // Two pins: the map holds them exactly (written with 17 digits, read back to the bit); the errors of a
  // pins file name its line.
  const auto dir = iarap::test::temp_dir("param_cli_pins");
  const iarap::test::TestMesh cap = iarap::test::spherical_cap(5, 16, 0.5 * M_PI);
  iarap::write_mesh((dir / "cap.off").string(), cap.V, cap.F);
  write_file(dir / "pins.txt", "# vertex u v\n0 1.5 -2\n7 3.25 -2\n");
  const std::string base = "param " + quoted(dir / "cap.off") + " --out " + quoted(dir / "uv.txt");
  const CliRun run = iarap_cli(base + " --pins " + quoted(dir / "pins.txt") + " --json --quiet");
  ASSERT_EQ(run.code, 0) << run.out;
  const nlohmann::json j = parse_json(run);
  EXPECT_EQ(j["pins"], 2);
  EXPECT_EQ(j["pinned"], 2);
  EXPECT_EQ(j["flipped"], 0);
  std::istringstream uv(read_file(dir / "uv.txt"));
  std::vector<std::pair<double, double>> rows;
  for (double u, v; uv >> u >> v;) rows.emplace_back(u, v);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(cap.V.rows()));
  EXPECT_EQ(rows[0], std::make_pair(1.5, -2.0));
  EXPECT_EQ(rows[7], std::make_pair(3.25, -2.0));
  const struct {
    std::string text, says;
  } bad[] = {
      {"0 1 2\n9999 0 0\n", "pins.txt:2"},   {"0 1 2 3\n", "two coordinates"},
      {"0 1 2 0 5\n", "UV pins are hard"},   {"0 1 nan\n", "pins.txt:1"},
      {"0 1 2\n3 1 2\n", "one UV position"},
  };
  for (const auto& c : bad) {
    write_file(dir / "pins.txt", c.text);
    const CliRun failed = iarap_cli(base + " --pins " + quoted(dir / "pins.txt") + " --quiet", true);
    EXPECT_EQ(failed.code, 1) << c.text << failed.out;
    EXPECT_NE(failed.out.find(c.says), std::string::npos) << c.text << failed.out;
  }
  fs::remove_all(dir);
}

// `iarap param` on `mesh` written as file `name` in a fresh folder, with `options` and --json; the report,
// or an empty object after a recorded failure.
nlohmann::json param_report(const iarap::test::TestMesh& mesh, const std::string& name,
                            const std::string& options) {
  const auto dir = iarap::test::temp_dir("param_cli_" + name);
  iarap::write_mesh((dir / name).string(), mesh.V, mesh.F);
  const CliRun run =
      iarap_cli("param " + quoted(dir / name) + " --out " + quoted(dir / "uv.txt") + " --json " + options);
  fs::remove_all(dir);
  EXPECT_EQ(run.code, 0) << run.out;
  return run.code == 0 ? parse_json(run) : nlohmann::json::object();
}

TEST(ParamCommand, PerVertexEnergy) {
  const nlohmann::json j =
      param_report(iarap::test::spherical_cap(6, 18, 0.6 * M_PI), "cap.obj", "--energy iarap --quiet");
  EXPECT_EQ(j["energy_kind"], "iarap");
  EXPECT_EQ(j["flipped"], 0);
  EXPECT_LT(j["energies"].back().get<double>(), j["initial_energy"].get<double>());
}

TEST(ParamCommand, CircularBoundaryDefaultsToHarmonic) {
  const nlohmann::json j =
      param_report(iarap::test::spherical_cap(5, 14, 0.4 * M_PI), "cap.ply", "--boundary circle");
  EXPECT_EQ(j["requested_init"], "harmonic");
  EXPECT_EQ(j["boundary"], "circle");
  EXPECT_EQ(j["flipped"], 0);
}

} // namespace
