// The tufted cover (src/intrinsic/tufted_cover.h): an oriented closed surface over any triangle mesh, and
// the signpost triangulation built on it.
#include "intrinsic/signpost_triangulation.h"
#include "intrinsic/tufted_cover.h"

#include "iarap/core/errors.h"
#include "iarap/io/read_mesh.h"
#include "iarap/mesh/edge_topology.h"
#include "mesh/corner_fans.h"
#include "mesh/small_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

using namespace iarap;
using iarap::test::SmallMesh;

namespace {

detail::TuftedCover cover_of(const SmallMesh& m) {
  return detail::tufted_cover(m.V, m.F, edge_topology(m.F, static_cast<int>(m.V.rows())));
}

int tail(const detail::TuftedCover& c, int h) {
  return c.F(h / 3, h % 3);
}
int head(const detail::TuftedCover& c, int h) {
  return c.F(h / 3, (h + 1) % 3);
}

// What makes the cover an oriented closed surface: every halfedge glued to one running back along the
// same cover edge, over the same input edge; each cover vertex copies the input vertex of its corners.
void expect_closed_oriented(const SmallMesh& m, const detail::TuftedCover& c, const std::string& what) {
  ASSERT_EQ(c.F.rows(), 2 * m.F.rows()) << what;
  ASSERT_EQ(c.twin.size(), static_cast<size_t>(6 * m.F.rows())) << what;
  for (int h = 0; h < static_cast<int>(c.twin.size()); ++h) {
    const int t = c.twin[static_cast<size_t>(h)];
    ASSERT_GE(t, 0) << what << ": halfedge " << h << " is not glued";
    EXPECT_EQ(c.twin[static_cast<size_t>(t)], h) << what;
    EXPECT_EQ(tail(c, t), head(c, h)) << what << ": halfedge " << h;
    EXPECT_EQ(head(c, t), tail(c, h)) << what << ": halfedge " << h;
  }
  for (int g = 0; g < c.F.rows(); ++g) {
    const int f = detail::input_face(g);
    const std::set<int> input{m.F(f, 0), m.F(f, 1), m.F(f, 2)};
    const std::set<int> copied{c.vertex(c.F(g, 0)), c.vertex(c.F(g, 1)), c.vertex(c.F(g, 2))};
    EXPECT_EQ(copied, input) << what << ": cover face " << g;
    EXPECT_EQ(c.V.row(c.F(g, 0)), m.V.row(c.vertex(c.F(g, 0)))) << what;
  }
  // Front (a, b, c) and back (a, c, b): the back copy runs the other way.
  for (int f = 0; f < m.F.rows(); ++f) {
    EXPECT_EQ(c.vertex(c.F(2 * f, 1)), m.F(f, 1)) << what;
    EXPECT_EQ(c.vertex(c.F(2 * f + 1, 1)), m.F(f, 2)) << what;
  }
}

// Builds the signpost triangulation of the cover, which checks that every cover vertex has one closed fan,
// and returns sum_v (2 pi - Theta_v) / (2 pi), which Gauss-Bonnet makes the cover's Euler characteristic.
double signpost_euler_characteristic(const detail::TuftedCover& c) {
  detail::VertexFans fans;
  const detail::SignpostTriangulation tri =
      detail::build_glued_signpost_triangulation(c.V, c.F, c.twin, false, 0.0, fans);
  double defect = 0.0;
  for (int v = 0; v < tri.num_vertices; ++v) {
    EXPECT_FALSE(tri.boundary_vertex[static_cast<size_t>(v)]);
    defect += 2 * M_PI - tri.vertex_angle_sum[static_cast<size_t>(v)];
  }
  EXPECT_EQ(tri.num_edges(), 3 * c.F.rows() / 2);
  return defect / (2 * M_PI);
}

int euler_characteristic(const detail::TuftedCover& c) {
  return static_cast<int>(c.vertex.size()) - static_cast<int>(3 * c.F.rows() / 2) +
         static_cast<int>(c.F.rows());
}

} // namespace

// One triangle: front and back glued along all three edges, a sphere of 3 vertices (chi = 2).
TEST(TuftedCover, OneTriangleIsADoubledDisk) {
  SmallMesh m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.F.resize(1, 3);
  m.F << 0, 1, 2;
  const detail::TuftedCover c = cover_of(m);
  expect_closed_oriented(m, c, "triangle");
  EXPECT_EQ(c.vertex.size(), 3);
  for (int h = 0; h < 3; ++h) EXPECT_EQ(c.twin[static_cast<size_t>(h)] / 3, 1) << "front glued to back";
  EXPECT_EQ(euler_characteristic(c), 2);
  EXPECT_NEAR(signpost_euler_characteristic(c), 2.0, 1e-12);
  EXPECT_EQ(c.max_edge_faces, 1);
}

// A closed oriented mesh: the cover is two copies of it, fronts glued to fronts and backs to backs.
TEST(TuftedCover, ClosedMeshIsTwoCopies) {
  const SmallMesh m = iarap::test::subdivided_octahedron();
  const detail::TuftedCover c = cover_of(m);
  expect_closed_oriented(m, c, "octahedron");
  EXPECT_EQ(c.vertex.size(), 2 * m.V.rows());
  for (int h = 0; h < static_cast<int>(c.twin.size()); ++h)
    EXPECT_EQ((h / 3) % 2, (c.twin[static_cast<size_t>(h)] / 3) % 2) << "halfedge " << h;
  EXPECT_EQ(euler_characteristic(c), 4);
  EXPECT_NEAR(signpost_euler_characteristic(c), 4.0, 1e-9);
}

// Two cubes at a corner: each cube's front and back are closed surfaces of their own, so the shared corner
// has four copies and every other vertex two.
TEST(TuftedCover, CubesAtACornerSplitTheCorner) {
  const SmallMesh m = iarap::test::two_cubes_at_a_corner();
  const detail::TuftedCover c = cover_of(m);
  expect_closed_oriented(m, c, "cubes");
  EXPECT_EQ(c.vertex.size(), 32);
  EXPECT_EQ((c.vertex.array() == 0).count(), 4);
  EXPECT_EQ(euler_characteristic(c), 8);
  EXPECT_NEAR(signpost_euler_characteristic(c), 8.0, 1e-9);
}

// Fins of 3 to 5 faces on one edge, of mixed orientation: each face is glued to its two neighbours in
// angular order around the edge (the faces are numbered in that order), never across another face.
TEST(TuftedCover, FinGluesFacesInAngularOrder) {
  for (int k = 3; k <= 5; ++k) {
    const SmallMesh m = iarap::test::fin(k);
    const detail::TuftedCover c = cover_of(m);
    const std::string what = std::to_string(k) + " faces";
    expect_closed_oriented(m, c, what);
    EXPECT_EQ(c.max_edge_faces, k);
    std::set<std::pair<int, int>> glued;
    for (int h = 0; h < static_cast<int>(c.twin.size()); ++h) {
      const std::set<int> ends{c.vertex(tail(c, h)), c.vertex(head(c, h))};
      if (ends != std::set<int>{0, 1}) continue;
      const int f = detail::input_face(h / 3), g = detail::input_face(c.twin[static_cast<size_t>(h)] / 3);
      EXPECT_TRUE((f + 1) % k == g || (g + 1) % k == f) << what << ": faces " << f << " and " << g;
      glued.insert({std::min(f, g), std::max(f, g)});
    }
    EXPECT_EQ(glued.size(), static_cast<size_t>(k)) << what; // every wedge closed once
    // All faces meet at the fin's edge, and each face's free edges glue its front to its back: one copy of
    // each vertex. chi = V - E + F = (k + 2) - (k + 2k) + 2k = 2.
    EXPECT_EQ(c.vertex.size(), k + 2) << what;
    EXPECT_NEAR(signpost_euler_characteristic(c), euler_characteristic(c), 1e-9) << what;
  }
}

// Non-orientable input: the Klein bottle's cover is its orientation double cover (a torus, chi = 0, two
// copies of every vertex); the Moebius strip's is a torus too (the annulus that double-covers it, its two
// boundary circles glued front to back), with one copy of each vertex (all are on the boundary).
TEST(TuftedCover, NonOrientableInputGivesAnOrientedCover) {
  const SmallMesh klein = iarap::test::klein_bottle(12, 8);
  const detail::TuftedCover k = cover_of(klein);
  expect_closed_oriented(klein, k, "klein");
  EXPECT_EQ(k.vertex.size(), 2 * klein.V.rows());
  EXPECT_EQ(euler_characteristic(k), 0);
  EXPECT_NEAR(signpost_euler_characteristic(k), 0.0, 1e-9);
  const SmallMesh strip = iarap::test::moebius_strip();
  const detail::TuftedCover s = cover_of(strip);
  expect_closed_oriented(strip, s, "moebius");
  EXPECT_EQ(s.vertex.size(), strip.V.rows());
  EXPECT_EQ(euler_characteristic(s), 0);
  EXPECT_NEAR(signpost_euler_characteristic(s), 0.0, 1e-9);
}

TEST(TuftedCover, OrientedManifoldTest) {
  const auto oriented_manifold = [](const SmallMesh& m) {
    return detail::is_oriented_manifold(m.F, edge_topology(m.F, static_cast<int>(m.V.rows())),
                                        static_cast<int>(m.V.rows()));
  };
  const SmallMesh sphere = iarap::test::subdivided_octahedron();
  EXPECT_TRUE(oriented_manifold(sphere));
  // With a hole (the faces at vertex 0 taken out): the fans around the hole are open, one per vertex.
  SmallMesh holed = sphere;
  int kept = 0;
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f)
    if ((sphere.F.row(f).array() != 0).all()) holed.F.row(kept++) = sphere.F.row(f);
  holed.F.conservativeResize(kept, 3);
  ASSERT_LT(kept, sphere.F.rows());
  EXPECT_TRUE(oriented_manifold(holed));
  // The walk around the vertices that decides these without grouping corners: one fan at every vertex of
  // the sphere and the holed sphere, two at the cones' tip and the bowtie's middle (below).
  const auto one_fan = [](const SmallMesh& m) {
    return detail::every_vertex_has_one_fan(m.F, edge_topology(m.F, static_cast<int>(m.V.rows())),
                                            static_cast<int>(m.V.rows()));
  };
  EXPECT_TRUE(one_fan(sphere));
  EXPECT_TRUE(one_fan(holed));
  EXPECT_FALSE(one_fan(iarap::test::two_cones_sharing_a_tip()));
  EXPECT_FALSE(oriented_manifold(iarap::test::with_mixed_orientation(sphere, 7)));
  EXPECT_FALSE(oriented_manifold(iarap::test::two_cubes_at_a_corner()));
  EXPECT_FALSE(oriented_manifold(iarap::test::two_cones_sharing_a_tip()));
  EXPECT_FALSE(oriented_manifold(iarap::test::fin(3)));
  EXPECT_FALSE(oriented_manifold(iarap::test::moebius_strip()));
  EXPECT_FALSE(oriented_manifold(iarap::test::klein_bottle(12, 8)));
  // Two triangles touching at a vertex (open fans, a bowtie): today's path takes it.
  SmallMesh bowtie;
  bowtie.V.resize(5, 3);
  bowtie.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  bowtie.F.resize(2, 3);
  bowtie.F << 0, 1, 2, 0, 3, 4;
  EXPECT_TRUE(oriented_manifold(bowtie));
  EXPECT_FALSE(one_fan(bowtie));
}

// The glued build refuses twins that do not pair opposite halfedges, naming the halfedge.
TEST(TuftedCover, GluedBuildRefusesBadTwins) {
  SmallMesh m;
  m.V.resize(3, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 1, 2; // the same direction twice
  const std::vector<int> twin{3, 4, 5, 0, 1, 2};
  detail::VertexFans fans;
  try {
    detail::build_glued_signpost_triangulation(m.V, m.F, twin, false, 0.0, fans);
    ADD_FAILURE() << "expected a TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("halfedge 0 (0, 1)"), std::string::npos) << e.what();
  }
}

// The walk around each vertex against the grouping of every corner into fans (pinched_vertices) on the
// shared meshes, dirty ones included: on every mesh whose edges the walk's premise holds for (at most two
// faces, traversed both ways), one fan at every vertex exactly where the grouping finds no pinched vertex.
TEST(TuftedCover, FanWalkAgreesWithCornerGroupsOnSharedMeshes) {
  int compared = 0, several = 0;
  for (const char* name : {"planexy.off",     "grid.off",       "cube.obj",      "decimated-knight.off",
                           "spike.ply",       "halftunnel.off", "bunny.off",     "3holes.off",
                           "fertility.off",   "horse.obj",      "cactus.obj",    "elephant.obj",
                           "cheburashka.off", "lion.off",       "camelhead.off", "armadillo_30K.obj",
                           "beetle.off",      "bumpy-cube.obj", "face.obj",      "ogre.obj"}) {
    const std::string path = iarap::test::shared_mesh_in_loop(name);
    if (path.empty()) continue;
    const iarap::MeshData mesh = iarap::read_mesh(path);
    const int n = static_cast<int>(mesh.V.rows());
    const iarap::EdgeTopology t = edge_topology(mesh.F, n);
    if (!detail::edges_are_oriented_manifold(mesh.F, t)) continue;
    const iarap::mesh_checks::PinchedVertices pinched = iarap::mesh_checks::pinched_vertices(mesh.F, t, n);
    EXPECT_EQ(detail::every_vertex_has_one_fan(mesh.F, t, n), pinched.open.empty() && pinched.closed.empty())
        << name;
    ++compared;
    several += pinched.open.empty() && pinched.closed.empty() ? 0 : 1;
  }
  std::printf("fan walk compared on %d meshes, %d with several fans at a vertex\n", compared, several);
}
