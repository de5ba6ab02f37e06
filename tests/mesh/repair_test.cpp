#include "iarap/core/errors.h"
#include "iarap/mesh/repair.h"
#include "iarap/mesh/validate.h"
#include "small_meshes.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

TEST(RepairMesh, WeldsASoupBackIntoOneComponent) {
  const auto octa = iarap::test::octahedron();
  auto soup = iarap::test::as_soup(octa);
  // Jitter one copy well inside the tolerance (1e-12 x diagonal ~ 3.5e-12) to test the tolerance path.
  soup.V(5, 0) += 1e-13;
  const iarap::RepairResult r = iarap::repair_mesh(soup.V, soup.F);
  ASSERT_EQ(r.V.rows(), 6);
  ASSERT_EQ(r.F.rows(), 8);
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  EXPECT_TRUE(report.usable());
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(report.genus, 0);
  EXPECT_EQ(report.coincident_vertices, 0);
  // Each old corner maps to the welded vertex at its position.
  for (Eigen::Index v = 0; v < soup.V.rows(); ++v) {
    ASSERT_GE(r.old_to_new(v), 0);
    EXPECT_LE((r.V.row(r.old_to_new(v)) - soup.V.row(v)).norm(), 1e-12);
  }
  ASSERT_FALSE(r.actions.empty());
  EXPECT_NE(r.actions[0].find("welded 18 vertices"), std::string::npos) << r.actions[0];
}

TEST(RepairMesh, ToleranceSeparatesNearbyVertices) {
  auto soup = iarap::test::as_soup(iarap::test::octahedron());
  soup.V(5, 0) += 1e-6; // far outside 1e-12 x diagonal: stays its own vertex
  EXPECT_EQ(iarap::repair_mesh(soup.V, soup.F).V.rows(), 7);
  iarap::RepairOptions loose;
  loose.weld_tolerance = 1e-3;
  EXPECT_EQ(iarap::repair_mesh(soup.V, soup.F, loose).V.rows(), 6);
}

TEST(RepairMesh, RemovesUnreferencedAndZeroAreaKeepingOrder) {
  Eigen::MatrixXd V(6, 3);
  V << 0, 0, 0, 9, 9, 9, 1, 0, 0, 0, 1, 0, 2, 0, 0, 1, 1, 0;
  Eigen::MatrixXi F(3, 3);
  F << 0, 2, 3, 2, 5, 3, 0, 2, 4; // the last face is flat
  iarap::RepairOptions options;
  options.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(V, F, options);
  Eigen::VectorXi expected(6);
  expected << 0, -1, 1, 2, -1, 3; // vertex 1 unused, vertex 4 only in the flat face
  EXPECT_EQ(r.old_to_new, expected);
  ASSERT_EQ(r.F.rows(), 2);
  EXPECT_EQ(r.F.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(r.V.row(3), V.row(5));
  EXPECT_EQ(r.actions.size(), 2u);

  const iarap::RepairResult keep = iarap::repair_mesh(V, F); // defaults keep zero-area faces
  EXPECT_EQ(keep.F.rows(), 3);
  EXPECT_EQ(keep.V.rows(), 5);
}

TEST(RepairMesh, WeldingDropsCollapsedFaces) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0; // vertex 3 duplicates vertex 1
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 1, 3, 2;
  const iarap::RepairResult r = iarap::repair_mesh(V, F);
  EXPECT_EQ(r.F.rows(), 1);
  EXPECT_EQ(r.old_to_new(3), 1);
}

TEST(RepairMesh, OutOfRangeIndexThrows) {
  auto m = iarap::test::octahedron();
  m.F(4, 2) = 17;
  try {
    iarap::repair_mesh(m.V, m.F);
    ADD_FAILURE() << "expected InputError";
  } catch (const iarap::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 4 uses vertex 17"), std::string::npos) << e.what();
  }
}

// Repair at 1e-300: areas there underflow to 0 unless computed on normalised coordinates, so every face
// was "zero area" and dropped.
TEST(Repair, TinyScaleKeepsEveryFace) {
  const auto m = iarap::test::octahedron();
  iarap::RepairOptions options;
  options.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(m.V * 1e-300, m.F, options);
  EXPECT_EQ(r.F.rows(), m.F.rows());
  EXPECT_TRUE(r.actions.empty());
}

namespace {

using iarap::test::SmallMesh;

void reverse_face(Eigen::MatrixXi& F, Eigen::Index f) {
  std::swap(F(f, 1), F(f, 2));
}

bool has_action(const iarap::RepairResult& r, const std::string& part) {
  for (const auto& a : r.actions)
    if (a.find(part) != std::string::npos) return true;
  return false;
}

} // namespace

TEST(RepairOrientation, FlipsTheMinorityBackToTheOriginal) {
  const SmallMesh m = iarap::test::subdivided_octahedron();
  SmallMesh bad = m;
  for (int f : {1, 7, 20}) reverse_face(bad.F, f);
  ASSERT_FALSE(iarap::check_mesh(bad.V, bad.F).usable());
  const iarap::RepairResult r = iarap::repair_mesh(bad.V, bad.F);
  EXPECT_EQ(r.counts.flipped_faces, 3);
  EXPECT_EQ(r.F, m.F); // the three reversed faces come back; every other face is as it was
  EXPECT_EQ(r.V, m.V);
  EXPECT_TRUE(iarap::check_mesh(r.V, r.F).usable());
  EXPECT_TRUE(has_action(r, "reversed 3 faces")) << r.actions.front();
}

TEST(RepairOrientation, KeepsTheOrientationMostFacesHave) {
  const SmallMesh m = iarap::test::subdivided_octahedron();
  SmallMesh bad = m;
  for (Eigen::Index f = 2; f < bad.F.rows(); ++f) reverse_face(bad.F, f); // 30 of 32 reversed
  const iarap::RepairResult r = iarap::repair_mesh(bad.V, bad.F);
  EXPECT_EQ(r.counts.flipped_faces, 2);
  Eigen::MatrixXi inward = m.F;
  for (Eigen::Index f = 0; f < inward.rows(); ++f) reverse_face(inward, f);
  EXPECT_EQ(r.F, inward);
}

TEST(RepairOrientation, EachComponentOnItsOwn) {
  // Two spheres side by side: the second entirely reversed (consistent by itself: kept), the first with
  // one reversed face.
  const SmallMesh m = iarap::test::subdivided_octahedron();
  Eigen::MatrixXd shifted = m.V;
  shifted.col(0).array() += 5;
  Eigen::MatrixXi second = m.F.array() + static_cast<int>(m.V.rows());
  for (Eigen::Index f = 0; f < second.rows(); ++f) reverse_face(second, f);
  SmallMesh two = iarap::test::appended(m, shifted, second);
  reverse_face(two.F, 4);
  const iarap::RepairResult r = iarap::repair_mesh(two.V, two.F);
  EXPECT_EQ(r.counts.flipped_faces, 1);
  EXPECT_EQ(r.F.topRows(m.F.rows()), m.F);
  EXPECT_EQ(r.F.bottomRows(second.rows()), second);
}

TEST(RepairOrientation, MoebiusStripIsLeftAsItIsAndNamed) {
  const SmallMesh strip = iarap::test::moebius_strip();
  const iarap::RepairResult r = iarap::repair_mesh(strip.V, strip.F);
  EXPECT_EQ(r.counts.non_orientable_pieces, 1);
  EXPECT_EQ(r.counts.flipped_faces, 0);
  EXPECT_EQ(r.F, strip.F);
  EXPECT_TRUE(has_action(r, "1 non-orientable piece"));
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  ASSERT_FALSE(report.usable());
  EXPECT_NE(report.errors.front().find("non-orientable"), std::string::npos) << report.errors.front();
  EXPECT_NE(report.errors.front().find("Moebius"), std::string::npos) << report.errors.front();
  EXPECT_NE(report.errors.front().find("the component of face"), std::string::npos) << report.errors.front();
}

TEST(RepairSplit, VertexWhereTwoClosedFansTouchGetsACopy) {
  const SmallMesh m = iarap::test::two_cones_sharing_a_tip();
  const iarap::RepairResult r = iarap::repair_mesh(m.V, m.F);
  EXPECT_EQ(r.counts.split_vertices, 1);
  EXPECT_EQ(r.counts.vertex_copies, 1);
  ASSERT_EQ(r.V.rows(), 10);
  EXPECT_EQ(r.new_to_old(9), 0);
  EXPECT_EQ(r.old_to_new(0), 0); // the first fan (the upper cone's, faces 0-5) keeps the index
  EXPECT_EQ(r.V.row(9), m.V.row(0));
  for (Eigen::Index f = 0; f < 12; ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.F(f, k), m.F(f, k) == 0 && f >= 6 ? 9 : m.F(f, k)) << "face " << f;
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  EXPECT_TRUE(report.usable());
  EXPECT_EQ(report.non_manifold_vertices, 0);
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.genus, 0);
}

TEST(RepairSplit, OpenFansStayJoinedUnlessAsked) {
  // A bowtie: two triangles meeting at vertex 0 only, each fan open.
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 4;
  EXPECT_EQ(iarap::repair_mesh(V, F).V.rows(), 5);
  iarap::RepairOptions split;
  split.split_open_fans = true;
  const iarap::RepairResult r = iarap::repair_mesh(V, F, split);
  EXPECT_EQ(r.counts.split_vertices, 1);
  ASSERT_EQ(r.V.rows(), 6);
  EXPECT_EQ(r.F.row(1), Eigen::RowVector3i(5, 3, 4));
}

TEST(RepairSplit, FinOnAnEdgeIsSeparatedFromTheSurface) {
  const SmallMesh m = iarap::test::octahedron();
  // The fin (0, 2, 6) stands on edge (0, 2) of faces 0 and 4, its tip straight out: at 125 degrees to
  // either face, flatter than the 109 degrees between them, yet the faces of one piece pair first.
  const SmallMesh fin =
      iarap::test::appended(m, Eigen::RowVector3d(1.5, 1.5, 0), Eigen::RowVector3i(0, 2, 6));
  ASSERT_EQ(iarap::check_mesh(fin.V, fin.F).non_manifold_edges, 1);
  const iarap::RepairResult r = iarap::repair_mesh(fin.V, fin.F);
  EXPECT_EQ(r.counts.split_edges, 1);
  EXPECT_EQ(r.counts.split_vertices, 2);
  EXPECT_EQ(r.F.topRows(8), m.F); // the octahedron keeps its vertices
  EXPECT_EQ(r.F.row(8), Eigen::RowVector3i(7, 8, 6));
  EXPECT_EQ(r.new_to_old.tail(2), Eigen::Vector2i(0, 2));
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  EXPECT_TRUE(report.usable()) << report.errors.front();
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.genus, 0); // octahedron (genus 0) + a disk (genus 0)
}

TEST(RepairSplit, TwoSheetsCrossingAlongAnEdgeStaySheets) {
  // Four faces on edge (0, 1) along z, third vertices at +x, +y, -x, -y in that face order: the flattest
  // pairs are (+x, -x) and (+y, -y), cosine -1 each.
  Eigen::MatrixXd V(6, 3);
  V << 0, 0, 0, 0, 0, 1, 1, 0, 0.5, 0, 1, 0.5, -1, 0, 0.5, 0, -1, 0.5;
  Eigen::MatrixXi F(4, 3);
  F << 0, 1, 2, 0, 1, 3, 1, 0, 4, 1, 0, 5;
  const iarap::RepairResult r = iarap::repair_mesh(V, F);
  EXPECT_EQ(r.counts.split_edges, 1);
  EXPECT_EQ(r.counts.vertex_copies, 2);
  // Faces 0 and 2 keep (0, 1); faces 1 and 3 share the copies 6 and 7 of 0 and 1.
  EXPECT_EQ(r.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(r.F.row(2), Eigen::RowVector3i(1, 0, 4));
  EXPECT_EQ(r.F.row(1), Eigen::RowVector3i(6, 7, 3));
  EXPECT_EQ(r.F.row(3), Eigen::RowVector3i(7, 6, 5));
  const iarap::MeshReport report = iarap::check_mesh(r.V, r.F);
  EXPECT_TRUE(report.usable());
  EXPECT_EQ(report.components, 2);
  EXPECT_EQ(report.boundary_loops, 2);
}

TEST(RepairFaces, DuplicatesEitherWayRoundAreRemoved) {
  const SmallMesh m = iarap::test::octahedron();
  Eigen::MatrixXi extra(2, 3);
  extra << m.F.row(3), m.F(5, 0), m.F(5, 2), m.F(5, 1);
  const SmallMesh dup = iarap::test::appended(m, Eigen::MatrixXd(0, 3), extra);
  const iarap::RepairResult r = iarap::repair_mesh(dup.V, dup.F);
  EXPECT_EQ(r.counts.duplicate_faces, 2);
  EXPECT_EQ(r.F, m.F);
  EXPECT_TRUE(has_action(r, "removed 2 duplicate faces"));
}

TEST(RepairFaces, FaceRepeatingAVertexGoesWithZeroAreaFaces) {
  SmallMesh m =
      iarap::test::appended(iarap::test::octahedron(), Eigen::MatrixXd(0, 3), Eigen::RowVector3i(0, 0, 2));
  EXPECT_EQ(iarap::repair_mesh(m.V, m.F).F.rows(), 9); // kept by default: check_mesh then names it
  iarap::RepairOptions options;
  options.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(m.V, m.F, options);
  EXPECT_EQ(r.counts.repeated_vertex_faces, 1);
  EXPECT_EQ(r.F.rows(), 8);
  EXPECT_TRUE(iarap::check_mesh(r.V, r.F).usable());
}

TEST(RepairMesh, CleanMeshIsReturnedAsItIs) {
  const SmallMesh m = iarap::test::subdivided_octahedron();
  iarap::RepairOptions all;
  all.remove_zero_area = true;
  const iarap::RepairResult r = iarap::repair_mesh(m.V, m.F, all);
  EXPECT_EQ(r.V, m.V);
  EXPECT_EQ(r.F, m.F);
  EXPECT_EQ(r.new_to_old, Eigen::VectorXi::LinSpaced(18, 0, 17));
  EXPECT_TRUE(r.actions.empty());
}
