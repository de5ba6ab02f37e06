#include "iarap/io/read_mesh.h"
#include "iarap/mesh/validate.h"
#include "small_meshes.h"
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>
#include <regex>

using iarap::check_mesh;
using iarap::MeshReport;

namespace {

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& line : lines)
    if (line.find(part) != std::string::npos) return true;
  return false;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

MeshReport check_shared(const char* name) {
  const iarap::MeshData m = iarap::read_mesh(iarap::test::shared_mesh_path(name));
  return check_mesh(m.V, m.F);
}

#define SKIP_WITHOUT(name)                                                                                   \
  if (iarap::test::shared_mesh_path(name).empty()) {                                                         \
    if (iarap::test::shared_meshes_required())                                                               \
      FAIL() << name << " is missing and IARAP_REQUIRE_SHARED_MESHES=1";                                     \
    GTEST_SKIP() << name << " not found in the shared meshes";                                               \
  }

} // namespace

TEST(CheckMesh, CleanClosedBunny) {
  const iarap::MeshData m = iarap::read_mesh(iarap::test::data_path("bunny.off"));
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_TRUE(r.usable()) << joined(r.errors);
  EXPECT_TRUE(r.warnings.empty()) << joined(r.warnings);
  EXPECT_EQ(r.vertices, 3485);
  EXPECT_EQ(r.faces, 6966);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundary_loops, 0);
  EXPECT_EQ(r.boundary_edges, 0);
  ASSERT_TRUE(r.genus.has_value());
  EXPECT_EQ(*r.genus, 0);
  // README: about 9% of the 10449 edges are non-Delaunay.
  EXPECT_NEAR(r.non_delaunay_edges / 10449.0, 0.09, 0.01);
}

TEST(CheckMesh, OctahedronIsCleanAndDelaunay) {
  const auto m = iarap::test::octahedron();
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_TRUE(r.usable()) << joined(r.errors);
  EXPECT_EQ(r.genus, 0);
  EXPECT_EQ(r.non_delaunay_edges, 0);
  EXPECT_DOUBLE_EQ(r.bbox_diagonal, 2.0 * std::sqrt(3.0));
}

TEST(CheckMesh, GenusOfSharedMeshes) {
  SKIP_WITHOUT("3holes.off");
  EXPECT_EQ(check_shared("3holes.off").genus, 3);
  SKIP_WITHOUT("fertility.off");
  EXPECT_EQ(check_shared("fertility.off").genus, 4);
}

TEST(CheckMesh, HexGridFacesAreNonManifold) {
  SKIP_WITHOUT("cube_40k.obj");
  const MeshReport r = check_shared("cube_40k.obj");
  EXPECT_FALSE(r.usable());
  EXPECT_EQ(r.non_manifold_edges, 55580);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(any_contains(r.errors, "55580 edges are non-manifold")) << joined(r.errors);
}

TEST(CheckMesh, DirtyOgre) {
  SKIP_WITHOUT("ogre.obj");
  const MeshReport r = check_shared("ogre.obj");
  EXPECT_EQ(r.components, 44);
  EXPECT_EQ(r.zero_area_faces, 4);
  EXPECT_TRUE(any_contains(r.warnings, "4 faces have zero area")) << joined(r.warnings);
  EXPECT_GT(r.boundary_loops, 0);
}

TEST(CheckMesh, TwoConesSharingATip) {
  const auto m = iarap::test::two_cones_sharing_a_tip();
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.non_manifold_vertices, 1);
  EXPECT_EQ(r.inconsistently_oriented_edges, 0);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(any_contains(r.errors, "first: vertex 0")) << joined(r.errors);
}

TEST(CheckMesh, SoupWarnsAboutCoincidentVertices) {
  const auto soup = iarap::test::as_soup(iarap::test::octahedron());
  const MeshReport r = check_mesh(soup.V, soup.F);
  EXPECT_EQ(r.components, 8);
  EXPECT_EQ(r.coincident_vertices, 24 - 6);
  EXPECT_TRUE(any_contains(r.warnings, "coincide")) << joined(r.warnings);
  EXPECT_TRUE(any_contains(r.warnings, "one component per face")) << joined(r.warnings);
}

// Issue 36: the library names its own repair (repair_mesh and the option that does it), never a flag of
// the tool; `iarap info`, `deform` and the viewer put their own words in its place
// (app/common/explain_error.h).
TEST(CheckMesh, WarningsNameTheLibraryRepair) {
  auto soup = iarap::test::as_soup(iarap::test::octahedron());
  soup.V.conservativeResize(soup.V.rows() + 1, 3);
  soup.V.bottomRows(1) << 5, 5, 5;                                // used by no face
  soup.V.row(0) = soup.V.row(1) + Eigen::RowVector3d(1e-3, 0, 0); // face 0 becomes a sliver...
  soup.V.row(2) = soup.V.row(1) + Eigen::RowVector3d(2e-3, 0, 0); // ...of zero width: zero area
  const MeshReport r = check_mesh(soup.V, soup.F);
  ASSERT_EQ(r.warnings.size(), 4u) << joined(r.warnings);
  EXPECT_TRUE(any_contains(r.warnings, "first: vertex 24; repair_mesh removes them "
                                       "(RepairOptions::remove_unreferenced)"))
      << joined(r.warnings);
  EXPECT_TRUE(
      any_contains(r.warnings, "first: face 0; repair_mesh drops them (RepairOptions::remove_zero_area)"))
      << joined(r.warnings);
  EXPECT_TRUE(any_contains(r.warnings, "repair_mesh welds them (RepairOptions::weld)")) << joined(r.warnings);
  EXPECT_TRUE(any_contains(r.warnings, "(STL); repair_mesh welds it (RepairOptions::weld)"))
      << joined(r.warnings);
  for (const std::string& line : r.warnings) {
    EXPECT_EQ(line.find("iarap "), std::string::npos) << line;
    EXPECT_EQ(line.find("--"), std::string::npos) << line;
  }
}

TEST(CheckMesh, FlippedFace) {
  auto m = iarap::test::octahedron();
  std::swap(m.F(3, 1), m.F(3, 2));
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_EQ(r.inconsistently_oriented_edges, 3);
  EXPECT_TRUE(any_contains(r.errors, "inconsistently oriented")) << joined(r.errors);
  // The first such edge lies on face 3, the flipped one.
  EXPECT_TRUE(std::regex_search(joined(r.errors), std::regex("between faces (3 and [0-9]+|[0-9]+ and 3);")))
      << joined(r.errors);
}

TEST(CheckMesh, NonFiniteCoordinate) {
  auto m = iarap::test::octahedron();
  m.V(4, 1) = std::nan("");
  m.V(5, 2) = INFINITY;
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_EQ(r.non_finite_coordinates, 2);
  EXPECT_TRUE(any_contains(r.errors, "2 vertices have a NaN or Inf coordinate; first: vertex 4"))
      << joined(r.errors);
  EXPECT_TRUE(std::isfinite(r.bbox_diagonal));
}

TEST(CheckMesh, OutOfRangeAndGarbageIndicesNeverCrash) {
  auto m = iarap::test::octahedron();
  m.F(2, 1) = 6;
  m.F(5, 0) = -7;
  m.F(6, 2) = 2147483647;
  const MeshReport r = check_mesh(m.V, m.F);
  EXPECT_EQ(r.out_of_range_indices, 3);
  EXPECT_TRUE(any_contains(r.errors, "first: face 2 uses vertex 6; mesh has 6 vertices")) << joined(r.errors);
  // The faces left make an open surface; the checks still run on them.
  EXPECT_GT(r.boundary_edges, 0);

  Eigen::MatrixXi repeated = iarap::test::octahedron().F;
  repeated(1, 2) = repeated(1, 0);
  EXPECT_EQ(check_mesh(m.V, repeated).repeated_vertex_faces, 1);
  EXPECT_FALSE(check_mesh(m.V, Eigen::MatrixXi(2, 4)).usable());
  EXPECT_FALSE(check_mesh(Eigen::MatrixXd(0, 3), Eigen::MatrixXi(0, 3)).usable());
}

TEST(CheckMesh, UnreferencedZeroAreaAndNonDelaunay) {
  // A square split along the diagonal whose opposite angles are obtuse: (0,0) (4,0) (2,1) (2,-1),
  // diagonal (0)-(1) sees angles of 2 * atan(2) > 90 degrees on both sides, so its cotan weight is negative.
  Eigen::MatrixXd V(6, 3);
  V << 0, 0, 0, 4, 0, 0, 2, 1, 0, 2, -1, 0, 9, 9, 9, 1, 0, 0;
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 5, 1; // the last face is flat (collinear corners) and overlaps
  const MeshReport r = check_mesh(V, F);
  EXPECT_EQ(r.unreferenced_vertices, 1);
  EXPECT_TRUE(any_contains(r.warnings, "first: vertex 4")) << joined(r.warnings);
  EXPECT_EQ(r.zero_area_faces, 1);
  EXPECT_TRUE(any_contains(r.warnings, "first: face 2")) << joined(r.warnings);

  Eigen::MatrixXi G = F.topRows(2);
  const MeshReport kite = check_mesh(V, G);
  EXPECT_EQ(kite.non_delaunay_edges, 1);
  EXPECT_EQ(kite.boundary_loops, 1);
  EXPECT_EQ(kite.genus, 0);
}

TEST(CheckMesh, FlatGridRightAnglesAreNotNonDelaunay) {
  SKIP_WITHOUT("planexy.off");
  const MeshReport r = check_shared("planexy.off");
  EXPECT_EQ(r.non_delaunay_edges, 0);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.genus, 0);
}

// Issue 20: the Klein bottle (figure-8 immersion, 15 x 32 grid glued with a flip) has chi = 0 and no
// boundary, so the parity rule called it a torus (genus 1). Orientations propagated face to face find
// the contradiction.
TEST(CheckMesh, KleinBottleIsNonOrientable) {
  const int m = 15, n = 32; // m odd: the immersion's self-intersection circle (v = 0, pi) is sampled once
  const double pi = 3.14159265358979323846;
  Eigen::MatrixXd V(m * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      const double u = 2 * pi * j / n, v = 2 * pi * i / m;
      const double r = 3 + std::cos(u / 2) * std::sin(v) - std::sin(u / 2) * std::sin(2 * v);
      V.row(j * m + i) << r * std::cos(u), r * std::sin(u),
          std::sin(u / 2) * std::sin(v) + std::cos(u / 2) * std::sin(2 * v);
    }
  // Row n is row 0 with v -> -v: the gluing that makes the surface non-orientable.
  const auto index = [&](int i, int j) { return j == n ? (m - i % m) % m : j * m + i % m; };
  Eigen::MatrixXi F(2 * m * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      F.row(2 * (j * m + i)) << a, b, c;
      F.row(2 * (j * m + i) + 1) << a, c, d;
    }
  const MeshReport r = check_mesh(V, F);
  EXPECT_FALSE(r.orientable());
  EXPECT_EQ(r.non_orientable_components, 1);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_GT(r.inconsistently_oriented_edges, 0);
  EXPECT_TRUE(any_contains(r.errors, "non-orientable")) << joined(r.errors);
  // An orientable mesh with one face reversed is inconsistent but orientable, and says how to fix it.
  auto flipped = iarap::test::octahedron();
  std::swap(flipped.F(3, 1), flipped.F(3, 2));
  const MeshReport o = check_mesh(flipped.V, flipped.F);
  EXPECT_TRUE(o.orientable());
  EXPECT_TRUE(any_contains(o.errors, "the surface is orientable; repair_mesh reverses the faces"))
      << joined(o.errors);
}

// Issue 20: at 1e300 the diagonal overflowed (reported null) and every vertex "coincided"; at 1e-300 every
// face had "zero area". The report is the same at any scale, the diagonal in the file's units (relative
// 1e-14: the power-of-two normalisation is exact; stableNorm rounds differently from norm by a few ulp).
TEST(CheckMesh, ReportIsScaleInvariant) {
  const auto m = iarap::test::octahedron();
  for (double scale : {1e300, 1e-300, 1e80, 1e-80}) {
    const MeshReport r = check_mesh(m.V * scale, m.F);
    EXPECT_TRUE(r.usable()) << scale << ": " << joined(r.errors);
    EXPECT_TRUE(r.warnings.empty()) << scale << ": " << joined(r.warnings);
    EXPECT_EQ(r.coincident_vertices, 0) << scale;
    EXPECT_EQ(r.zero_area_faces, 0) << scale;
    EXPECT_EQ(r.genus, 0) << scale;
    EXPECT_NEAR(r.bbox_diagonal / scale, 2.0 * std::sqrt(3.0), 1e-14) << scale;
  }
}
