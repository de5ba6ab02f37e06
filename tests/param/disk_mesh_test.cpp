// boundary_loops and prepare_disk: the loops of small meshes built in code, and the refusal of every
// mesh that is not a topological disk, with messages that name what the mesh has.
#include "iarap/param/boundary_loops.h"
#include "iarap/param/disk_mesh.h"

#include "iarap/core/errors.h"
#include "mesh/small_meshes.h"
#include "param/disk_meshes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace iarap {
namespace {

using test::TestMesh;
using ::testing::HasSubstr;

// The message of the exception f throws, which must be of type E.
template <typename E, typename Function> std::string message_of(Function&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw another type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "did not throw";
  return {};
}

// Signed area enclosed by a loop of the planar mesh (shoelace formula).
double enclosed_area(const TestMesh& mesh, const std::vector<int>& loop) {
  double twice = 0;
  for (std::size_t p = 0; p < loop.size(); ++p) {
    const Eigen::RowVector3d a = mesh.V.row(loop[p]), b = mesh.V.row(loop[(p + 1) % loop.size()]);
    twice += a(0) * b(1) - a(1) * b(0);
  }
  return 0.5 * twice;
}

TEST(BoundaryLoops, SquareHasOneCounterClockwiseLoopThroughEveryBorderVertex) {
  const TestMesh square = test::flat_square(4);
  const auto loops = boundary_loops(square.F, static_cast<int>(square.V.rows()));
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 16u); // 4 sides of 4 edges
  EXPECT_EQ(loops[0].front(), 0);
  EXPECT_NEAR(enclosed_area(square, loops[0]), 1.0, 1e-15); // positive: counter-clockwise
}

TEST(BoundaryLoops, AnnulusHasTwoLoopsOfOppositeTurn) {
  const TestMesh annulus = test::flat_annulus(3, 12);
  const auto loops = boundary_loops(annulus.F, static_cast<int>(annulus.V.rows()));
  ASSERT_EQ(loops.size(), 2u);
  // The inner loop (vertices 0..11) runs clockwise around the hole, the outer one counter-clockwise.
  EXPECT_LT(enclosed_area(annulus, loops[0]), 0);
  EXPECT_GT(enclosed_area(annulus, loops[1]), 0);
}

TEST(BoundaryLoops, ClosedMeshHasNone) {
  const auto octahedron = test::octahedron();
  EXPECT_TRUE(boundary_loops(octahedron.F, 6).empty());
}

TEST(BoundaryLoops, TwoFansSharingAVertexAreRefusedNamingIt) {
  // Triangles (0 1 2) and (0 3 4) touch only at vertex 0: two boundary edges leave it.
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 4;
  EXPECT_THAT(message_of<TopologyError>([&] { boundary_loops(F, 5); }), HasSubstr("vertex 0"));
}

TEST(PrepareDisk, AcceptsADiskAndKeepsItsLoop) {
  const TestMesh disk_mesh = test::flat_disk(4, 16);
  const DiskMesh disk = prepare_disk(disk_mesh.V, disk_mesh.F);
  EXPECT_EQ(disk.boundary.size(), 16u);
  // The inscribed polygon of 16 sides: area (16 / 2) sin(2 pi / 16), to rounding.
  EXPECT_NEAR(disk.area, 8 * std::sin(2 * M_PI / 16), 1e-14);
  EXPECT_EQ(disk.frames.D.rows(), disk_mesh.F.rows());
}

TEST(PrepareDisk, RefusesAClosedMesh) {
  const auto octahedron = test::octahedron();
  const std::string message = message_of<TopologyError>([&] { prepare_disk(octahedron.V, octahedron.F); });
  EXPECT_THAT(message, HasSubstr("0 boundary loops and genus 0"));
  EXPECT_THAT(message, HasSubstr("cut it into disks first"));
}

TEST(PrepareDisk, RefusesAnAnnulus) {
  const TestMesh annulus = test::flat_annulus(3, 12);
  const std::string message = message_of<TopologyError>([&] { prepare_disk(annulus.V, annulus.F); });
  EXPECT_THAT(message, HasSubstr("2 boundary loops and genus 0"));
  EXPECT_THAT(message, HasSubstr("cut it into disks first"));
}

TEST(PrepareDisk, RefusesAHandle) {
  // A torus less one face: one boundary loop and genus 1 (chi = V - E + F = -1).
  const TestMesh torus = test::torus(6, 5);
  const Eigen::MatrixXi F = torus.F.bottomRows(torus.F.rows() - 1);
  const std::string message = message_of<TopologyError>([&] { prepare_disk(torus.V, F); });
  EXPECT_THAT(message, HasSubstr("1 boundary loop and genus 1"));
  EXPECT_THAT(message, HasSubstr("cut it into disks first"));
}

TEST(PrepareDisk, RefusesNaNNamingTheVertex) {
  TestMesh square = test::flat_square(2);
  square.V(4, 1) = std::nan("");
  const std::string message = message_of<InputError>([&] { prepare_disk(square.V, square.F); });
  EXPECT_THAT(message, HasSubstr("vertex 4"));
  EXPECT_THAT(message, HasSubstr("non-finite"));
}

TEST(PrepareDisk, RefusesADegenerateTriangleNamingIt) {
  TestMesh square = test::flat_square(2);
  // Vertex 1 onto the midpoint of vertices 0 and 4: face 0 = (0, 1, 4) then has three collinear corners
  // (the mesh stays a disk, every other face keeps its orientation).
  square.V.row(1) = 0.5 * (square.V.row(0) + square.V.row(4));
  const std::string message = message_of<TopologyError>([&] { prepare_disk(square.V, square.F); });
  EXPECT_THAT(message, HasSubstr("face 0 (vertices 0, 1, 4)"));
  EXPECT_THAT(message, HasSubstr("repair_mesh"));
}

TEST(PrepareDisk, RefusesUnusedVerticesAndBadIndices) {
  TestMesh square = test::flat_square(2);
  Eigen::MatrixXd V(square.V.rows() + 1, 3);
  V << square.V, Eigen::RowVector3d(5, 5, 5);
  EXPECT_THAT(message_of<TopologyError>([&] { prepare_disk(V, square.F); }), HasSubstr("vertex 9"));
  Eigen::MatrixXi F = square.F;
  F(3, 2) = 42;
  EXPECT_THAT(message_of<InputError>([&] { prepare_disk(square.V, F); }), HasSubstr("face 3 uses vertex 42"));
  EXPECT_THAT(message_of<InputError>([&] { prepare_disk(square.V.leftCols(2), square.F); }),
              HasSubstr("#V x 3"));
}

TEST(PrepareDisk, RefusesTwoComponents) {
  const TestMesh a = test::flat_square(2);
  Eigen::MatrixXd V(2 * a.V.rows(), 3);
  V << a.V, a.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
  Eigen::MatrixXi F(2 * a.F.rows(), 3);
  F << a.F, a.F.array() + static_cast<int>(a.V.rows());
  EXPECT_THAT(message_of<TopologyError>([&] { prepare_disk(V, F); }), HasSubstr("2 components"));
}

} // namespace
} // namespace iarap
