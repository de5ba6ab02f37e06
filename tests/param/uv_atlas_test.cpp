// uv_atlas: closed meshes of genus 0 and 1, several components and bad input become charts that are disks,
// flattened flip-free, without overlaps, packed inside the unit square; the parts (disk growth, packing,
// overlap checks) on cases whose answer is known exactly.
#include "iarap/param/uv_atlas.h"

#include "iarap/core/errors.h"
#include "iarap/mesh/subdivide.h"
#include "iarap/param/boundary_loops.h"
#include "mesh/small_meshes.h"
#include "param/chart_packing.h"
#include "param/disk_meshes.h"
#include "param/uv_overlap.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <map>
#include <set>

namespace iarap {
namespace {

// Every chart of the atlas is a topological disk: V - E + F = 1 and one boundary loop.
void expect_disk_charts(const Eigen::MatrixXi& F, const Eigen::VectorXi& chart, int charts) {
  for (int c = 0; c < charts; ++c) {
    std::map<int, int> local;
    std::vector<Eigen::Vector3i> faces;
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (chart(f) != c) continue;
      Eigen::Vector3i face;
      for (int k = 0; k < 3; ++k)
        face(k) = local.emplace(F(f, k), static_cast<int>(local.size())).first->second;
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(face(k), face((k + 1) % 3)));
      faces.push_back(face);
    }
    ASSERT_FALSE(faces.empty()) << "chart " << c;
    Eigen::MatrixXi Fc(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t i = 0; i < faces.size(); ++i)
      Fc.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
    EXPECT_EQ(
        static_cast<int>(local.size()) - static_cast<int>(edges.size()) + static_cast<int>(faces.size()), 1)
        << "chart " << c;
    EXPECT_EQ(boundary_loops(Fc, static_cast<int>(local.size())).size(), 1u) << "chart " << c;
  }
}

// What the issue asks of every atlas: no flipped triangle, no overlap, inside [0,1]^2.
void expect_valid_atlas(const Eigen::MatrixXi& F, const UvAtlas& atlas) {
  const AtlasReport& report = atlas.report;
  EXPECT_EQ(report.flipped, 0);
  EXPECT_EQ(report.boundary_overlaps, 0);
  EXPECT_LE(report.overlap_ratio, 1e-4);
  EXPECT_GE(atlas.corner_uv.minCoeff(), 0.0);
  EXPECT_LE(atlas.corner_uv.maxCoeff(), 1.0);
  for (const AtlasChart& chart : report.charts) EXPECT_EQ(chart.flipped, 0);
  expect_disk_charts(F, atlas.chart, static_cast<int>(report.charts.size()));
}

TEST(UvAtlas, TorusOfGenusOneIsCutIntoDiskCharts) {
  const test::TestMesh torus = test::torus(48, 24);
  const UvAtlas atlas = uv_atlas(torus.V, torus.F);
  expect_valid_atlas(torus.F, atlas);
  EXPECT_GE(atlas.report.charts.size(), 2u); // a torus is no disk
  EXPECT_GT(atlas.report.seam_length, 0.0);
  // Surface area 4 pi^2 R r = 8 pi^2 (the faceted torus a little less: within 1%).
  EXPECT_NEAR(atlas.report.area, 8 * M_PI * M_PI, 0.01 * 8 * M_PI * M_PI);
  // The bound on the area-weighted distortion, and the packing's.
  EXPECT_LE(atlas.report.distortion, 0.10);
  EXPECT_GE(atlas.report.packing_efficiency, 0.4);
}

TEST(UvAtlas, ClosedGenusZeroAndSeveralComponents) {
  // A unit sphere: the octahedron subdivided three times (512 faces), pushed onto the sphere.
  test::SmallMesh sphere = test::octahedron();
  subdivide_midpoint(sphere.V, sphere.F, 3);
  sphere.V.rowwise().normalize();
  const test::TestMesh torus = test::torus(24, 12);
  Eigen::MatrixXd V(sphere.V.rows() + torus.V.rows(), 3);
  V << sphere.V, torus.V.rowwise() + Eigen::RowVector3d(5, 0, 0);
  Eigen::MatrixXi F(sphere.F.rows() + torus.F.rows(), 3);
  F << sphere.F, torus.F.array() + static_cast<int>(sphere.V.rows());
  const UvAtlas atlas = uv_atlas(V, F);
  expect_valid_atlas(F, atlas);
  EXPECT_LE(atlas.report.distortion, 0.10);
  EXPECT_EQ(atlas.report.degenerate_faces, 0);
  // No chart spans both components.
  std::set<int> sphere_charts, torus_charts;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (atlas.chart(f) >= 0) (f < sphere.F.rows() ? sphere_charts : torus_charts).insert(atlas.chart(f));
  for (int c : sphere_charts) EXPECT_EQ(torus_charts.count(c), 0u);
}

TEST(UvAtlas, OctahedronAndDegenerateFaces) {
  const test::SmallMesh octahedron = test::octahedron();
  AtlasOptions options;
  options.min_chart_faces = 1;
  const UvAtlas atlas = uv_atlas(octahedron.V, octahedron.F, options);
  expect_valid_atlas(octahedron.F, atlas);
  // Adjacent octahedron faces turn by 109.5 degrees, more than the 60-degree cone: one face per chart,
  // each an equilateral triangle mapped isometrically (energy 0 up to the solver's rounding).
  EXPECT_EQ(atlas.report.charts.size(), 8u);
  EXPECT_LE(atlas.report.distortion, 1e-12);

  // A zero-area face (three collinear corners, a piece of its own) is kept out of the charts and put on
  // one UV point.
  const Eigen::Index n = octahedron.V.rows();
  Eigen::MatrixXd V(n + 3, 3);
  V << octahedron.V, Eigen::RowVector3d(3, 0, 0), Eigen::RowVector3d(4, 0, 0), Eigen::RowVector3d(5, 0, 0);
  Eigen::MatrixXi F(octahedron.F.rows() + 1, 3);
  F << octahedron.F,
      Eigen::RowVector3i(static_cast<int>(n), static_cast<int>(n + 1), static_cast<int>(n + 2));
  const UvAtlas with_degenerate = uv_atlas(V, F, options);
  EXPECT_EQ(with_degenerate.report.degenerate_faces, 1);
  EXPECT_EQ(with_degenerate.chart(F.rows() - 1), -1);
  const Eigen::Index last = 3 * (F.rows() - 1);
  EXPECT_EQ(with_degenerate.corner_uv.row(last), with_degenerate.corner_uv.row(last + 1));
  EXPECT_EQ(with_degenerate.corner_uv.row(last), with_degenerate.corner_uv.row(last + 2));
}

TEST(UvAtlas, DistortionSplitsACurvedChart) {
  // A hemisphere is one disk within a 180-degree cone; flattened whole its energy / area is far above a
  // target of 0.005, so it is split, and the parts' distortion is lower than the whole's.
  const test::TestMesh hemisphere = test::spherical_cap(16, 48, 0.5 * M_PI);
  AtlasOptions whole;
  whole.max_normal_angle = 180;
  whole.max_rounds = 0;
  const UvAtlas one = uv_atlas(hemisphere.V, hemisphere.F, whole);
  ASSERT_EQ(one.report.charts.size(), 1u);
  AtlasOptions split = whole;
  split.max_rounds = 8;
  split.target_distortion = 0.005;
  const UvAtlas parts = uv_atlas(hemisphere.V, hemisphere.F, split);
  expect_valid_atlas(hemisphere.F, parts);
  EXPECT_GT(parts.report.splits_for_distortion, 0);
  EXPECT_LT(parts.report.distortion, one.report.distortion);
}

TEST(UvAtlas, BadInputIsRefused) {
  // Three triangles on one edge: no chart can hold them as a disk.
  const test::SmallMesh fin = test::fin(3);
  try {
    uv_atlas(fin.V, fin.F);
    FAIL() << "a non-manifold edge was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be cut into disk charts"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("non-manifold"), std::string::npos) << e.what();
  }
  const test::TestMesh torus = test::torus(12, 6);
  AtlasOptions options;
  options.texture_size = 8;
  EXPECT_THROW(uv_atlas(torus.V, torus.F, options), InputError);
  options = {};
  options.max_normal_angle = 0;
  EXPECT_THROW(uv_atlas(torus.V, torus.F, options), InputError);
  options = {};
  options.param.pins.vertices = Eigen::VectorXi::Constant(1, 0);
  options.param.pins.uv = Eigen::MatrixXd::Zero(1, 2);
  EXPECT_THROW(uv_atlas(torus.V, torus.F, options), InputError);
  options = {};
  options.param.boundary = ParamBoundary::Circle;
  try {
    uv_atlas(torus.V, torus.F, options);
    FAIL() << "a circle boundary was accepted for an atlas";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("boundary circle does not apply to an atlas"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(uv_atlas(fin.V, Eigen::MatrixXi(0, 3)), InputError);
}

TEST(ChartPacking, FourEqualSquaresFillTheUnitSquare) {
  // Four unit squares, no gap: two shelves of two, each square scaled by 1/2; the packing is exact.
  Eigen::MatrixXd square(4, 2);
  square << 0, 0, 1, 0, 1, 1, 0, 1;
  Eigen::MatrixXi halves(2, 3);
  halves << 0, 1, 2, 0, 2, 3;
  const std::vector<Eigen::MatrixXd> charts(4, square);
  const std::vector<Eigen::MatrixXi> faces(4, halves);
  const param_detail::ChartPacking packing = param_detail::pack_charts(charts, faces, 64, 0);
  EXPECT_NEAR(packing.scale, 0.5, 1e-9);
  double area = 0;
  for (std::size_t c = 0; c < charts.size(); ++c) {
    const auto& p = packing.placements[c];
    EXPECT_NEAR(std::abs(p.rotation.determinant() - 1), 0, 1e-15);
    Eigen::MatrixXd uv =
        ((packing.scale * p.rotation * square.transpose()).colwise() + p.translation).transpose();
    EXPECT_GE(uv.minCoeff(), -1e-12);
    EXPECT_LE(uv.maxCoeff(), 1 + 1e-12);
    area += packing.scale * packing.scale;
  }
  EXPECT_NEAR(area, 1, 1e-8);
  // With a gap of g texels the squares shrink to (1 - 2 g / size) / 2.
  const param_detail::ChartPacking padded = param_detail::pack_charts(charts, faces, 64, 2);
  EXPECT_NEAR(padded.scale, (1 - 2 * 2.0 / 64) / 2, 1e-9);
}

TEST(ChartPacking, ATurnedRectangleLiesFlat) {
  // A 4 x 1 rectangle turned by 30 degrees: its minimum-area rectangle is itself, laid along u, so it
  // fills the square's width: scale 1 / 4.
  Eigen::MatrixXd rect(4, 2);
  rect << 0, 0, 4, 0, 4, 1, 0, 1;
  Eigen::Matrix2d turn;
  const double a = M_PI / 6;
  turn << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const Eigen::MatrixXd turned = (turn * rect.transpose()).transpose();
  Eigen::MatrixXi halves(2, 3);
  halves << 0, 1, 2, 0, 2, 3;
  const param_detail::ChartPacking packing = param_detail::pack_charts({turned}, {halves}, 64, 0);
  EXPECT_NEAR(packing.scale, 0.25, 1e-9);
}

TEST(UvOverlap, SelfCrossingLoopAndRasterizedOverlap) {
  Eigen::MatrixXd uv(4, 2);
  uv << 0, 0, 1, 0, 1, 1, 0, 1;
  EXPECT_FALSE(param_detail::loop_crosses_itself(uv, {0, 1, 2, 3}));
  EXPECT_TRUE(param_detail::loop_crosses_itself(uv, {0, 2, 1, 3})); // a bow tie
  // A triangle covering half the square, twice: every covered texel is covered twice; beside the other
  // half, none is.
  Eigen::MatrixXd corners(6, 2);
  corners << 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1;
  EXPECT_DOUBLE_EQ(param_detail::rasterized_overlap(corners, {true, true}, 64), 1.0);
  corners.bottomRows(3) << 1, 0, 1, 1, 0, 1;
  EXPECT_DOUBLE_EQ(param_detail::rasterized_overlap(corners, {true, true}, 64), 0.0);
}

} // namespace
} // namespace iarap
