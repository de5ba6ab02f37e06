// uv_atlas with what a caller adds to the mesh (AtlasInput): polygons kept in one chart, charts given with
// their layout (`--charts keep`), texture_seam_charts; and an atlas that does not depend on the threads.
#include "iarap/core/errors.h"
#include "iarap/core/threads.h"
#include "iarap/mesh/normalize_scale.h"
#include "iarap/param/arap_parameterize.h"
#include "iarap/param/disk_mesh.h"
#include "iarap/param/lscm.h"
#include "iarap/param/texture_seam_charts.h"
#include "iarap/param/uv_atlas.h"
#include "param/disk_meshes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

namespace iarap {
namespace {

using ::testing::HasSubstr;

// test::torus splits quad (a, b, d, c) into (a, b, d), (a, d, c): faces 2 q and 2 q + 1 are quad q, the
// fan of read_obj_textured.
std::vector<int> quads_of(const test::TestMesh& mesh) {
  std::vector<int> polygon(static_cast<std::size_t>(mesh.F.rows()));
  for (std::size_t f = 0; f < polygon.size(); ++f) polygon[f] = static_cast<int>(f / 2);
  return polygon;
}

void expect_valid(const UvAtlas& atlas) {
  EXPECT_EQ(atlas.report.flipped, 0);
  EXPECT_EQ(atlas.report.boundary_overlaps, 0);
  EXPECT_LE(atlas.report.overlap_ratio, 1e-4);
  EXPECT_LE(atlas.report.distortion, 0.10);
  EXPECT_GE(atlas.corner_uv.minCoeff(), 0.0);
  EXPECT_LE(atlas.corner_uv.maxCoeff(), 1.0);
}

TEST(UvAtlasInput, TheTrianglesOfAQuadShareAChartAndItsCornersUvs) {
  const test::TestMesh torus = test::torus(48, 24);
  AtlasInput input;
  input.polygon_of_face = quads_of(torus);
  const UvAtlas atlas = uv_atlas(torus.V, torus.F, {}, input);
  expect_valid(atlas);
  EXPECT_GE(atlas.report.charts.size(), 2u);
  for (Eigen::Index q = 0; q < torus.F.rows() / 2; ++q) {
    ASSERT_EQ(atlas.chart(2 * q), atlas.chart(2 * q + 1)) << "quad " << q;
    // The shared diagonal (a, d): corners 0 and 2 of the first triangle, 0 and 1 of the second.
    EXPECT_EQ(atlas.corner_uv.row(6 * q), atlas.corner_uv.row(6 * q + 3));
    EXPECT_EQ(atlas.corner_uv.row(6 * q + 2), atlas.corner_uv.row(6 * q + 4));
  }
}

TEST(UvAtlasInput, GivenChartsAreKeptAndStartFromTheirLayout) {
  const test::TestMesh torus = test::torus(48, 24);
  const UvAtlas first = uv_atlas(torus.V, torus.F);
  AtlasInput input;
  input.charts.assign(first.chart.data(), first.chart.data() + first.chart.size());
  input.corner_uv = first.corner_uv;
  const UvAtlas kept = uv_atlas(torus.V, torus.F, {}, input);
  expect_valid(kept);
  // The same partition (ids renumbered by first face, as the atlas numbers them too), each chart started
  // from the given layout: the first atlas's flattening scaled to its area, so near the same minimum.
  ASSERT_EQ(kept.report.charts.size(), first.report.charts.size());
  std::map<int, int> same;
  for (Eigen::Index f = 0; f < torus.F.rows(); ++f)
    EXPECT_EQ(same.emplace(first.chart(f), kept.chart(f)).first->second, kept.chart(f)) << "face " << f;
  for (const AtlasChart& chart : kept.report.charts) EXPECT_EQ(chart.started_from_input, 1);
  EXPECT_EQ(kept.report.splits_for_distortion, 0);
  // Both stop at the relative tolerance 1e-4 of the engine: their energies agree to about that.
  EXPECT_NEAR(kept.report.energy, first.report.energy, 1e-3 * first.report.energy);
}

TEST(UvAtlasInput, GivenChartThatIsNoDiskIsRefusedByName) {
  const test::TestMesh torus = test::torus(24, 12);
  AtlasInput input;
  input.charts.assign(static_cast<std::size_t>(torus.F.rows()), 7); // the whole torus one chart
  try {
    uv_atlas(torus.V, torus.F, {}, input);
    FAIL() << "a torus was taken as one chart";
  } catch (const TopologyError& e) {
    EXPECT_THAT(e.what(), HasSubstr("chart 0 of the texture seams"));
    EXPECT_THAT(e.what(), HasSubstr("not a topological disk"));
  }
  // A folded layout is not used as a start (each chart starts from LSCM instead): every triangle of a
  // small torus its own chart, laid out mirrored.
  const test::TestMesh small = test::torus(8, 4);
  input.charts = std::vector<int>(static_cast<std::size_t>(small.F.rows()));
  for (std::size_t f = 0; f < input.charts.size(); ++f) input.charts[f] = static_cast<int>(f);
  input.corner_uv = Eigen::MatrixXd::Zero(3 * small.F.rows(), 2);
  for (Eigen::Index f = 0; f < small.F.rows(); ++f) // (0,0), (0,1), (1,0): area < 0
    input.corner_uv.block(3 * f, 0, 3, 2) << 0, 0, 0, 1, 1, 0;
  const UvAtlas single = uv_atlas(small.V, small.F, {}, input);
  EXPECT_EQ(single.report.charts.size(), static_cast<std::size_t>(small.F.rows()));
  for (const AtlasChart& chart : single.report.charts) EXPECT_EQ(chart.started_from_input, 0);
  expect_valid(single);
}

TEST(UvAtlasInput, BadInputIsRefused) {
  const test::TestMesh torus = test::torus(12, 6);
  AtlasInput input;
  input.polygon_of_face = {0, 1};
  EXPECT_THROW(uv_atlas(torus.V, torus.F, {}, input), InputError);
  input = {};
  input.charts.assign(static_cast<std::size_t>(torus.F.rows()), 0);
  input.charts[3] = -1;
  EXPECT_THROW(uv_atlas(torus.V, torus.F, {}, input), InputError);
  input = {};
  input.corner_uv = Eigen::MatrixXd::Zero(3 * torus.F.rows(), 2); // a layout without charts
  EXPECT_THROW(uv_atlas(torus.V, torus.F, {}, input), InputError);
}

TEST(UvAtlasInput, TheAtlasDoesNotDependOnTheThreadCount) {
  const test::TestMesh torus = test::torus(48, 24);
  const int threads = thread_count();
  set_thread_count(1);
  const UvAtlas one = uv_atlas(torus.V, torus.F);
  set_thread_count(2);
  const UvAtlas two = uv_atlas(torus.V, torus.F);
  set_thread_count(threads);
  EXPECT_EQ(one.chart, two.chart);
  EXPECT_EQ(one.corner_uv, two.corner_uv); // bit for bit: each chart is flattened on one thread
}

TEST(InitialUv, AGivenStartIsUsedWhenItFoldsNothing) {
  const test::TestMesh disk = test::flat_disk(4, 16);
  const ParamResult plain = arap_parameterize(disk.V, disk.F);
  // LSCM's own map given as the start, computed as arap_parameterize does (on V / s, s a power of two): the
  // same iteration, so the same map to the bit.
  ParamOptions given;
  const double s = normalizing_scale(disk.V);
  given.initial_uv = lscm(prepare_disk(disk.V / s, disk.F)) * s;
  const ParamResult from_given = arap_parameterize(disk.V, disk.F, given);
  EXPECT_TRUE(from_given.report.initial_uv_used);
  EXPECT_FALSE(plain.report.initial_uv_used);
  EXPECT_EQ(from_given.UV, plain.UV);
  // Mirrored (every triangle folded): not used, the default start instead, so the default map.
  given.initial_uv.col(0) *= -1;
  const ParamResult mirrored = arap_parameterize(disk.V, disk.F, given);
  EXPECT_FALSE(mirrored.report.initial_uv_used);
  EXPECT_EQ(mirrored.UV, plain.UV);
  // Wrong size, or with pins: refused.
  given.initial_uv = Eigen::MatrixXd::Zero(3, 2);
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, given), InputError);
  given.initial_uv = plain.UV;
  given.pins.vertices = Eigen::VectorXi::Constant(1, 0);
  given.pins.uv = Eigen::MatrixXd::Zero(1, 2);
  EXPECT_THROW(arap_parameterize(disk.V, disk.F, given), InputError);
}

TEST(TextureSeamCharts, EdgesGlueWhereBothEndsShareTheirTextureIndices) {
  // Two triangles on the edge (1, 2): glued when both have vt 1 at vertex 1 and vt 2 at vertex 2.
  Eigen::MatrixXi F(2, 3), FT(2, 3);
  F << 0, 1, 2, 2, 1, 3;
  FT << 0, 1, 2, 2, 1, 3;
  EXPECT_EQ(texture_seam_charts(F, FT), (std::vector<int>{0, 0}));
  FT(1, 0) = 4; // vertex 2 has another vt in the second triangle: a seam
  EXPECT_EQ(texture_seam_charts(F, FT), (std::vector<int>{0, 1}));
  FT(1, 0) = -1;
  try {
    texture_seam_charts(F, FT);
    FAIL() << "a corner without a texture index was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("triangle 1"));
  }
}

TEST(PrepareChartDisk, ADiskAsPrepareDiskAndAnAnnulusRefused) {
  const test::TestMesh disk = test::flat_disk(3, 12);
  const DiskMesh checked = prepare_disk(disk.V, disk.F), trusted = prepare_chart_disk(disk.V, disk.F);
  EXPECT_EQ(trusted.boundary, checked.boundary);
  EXPECT_EQ(trusted.area, checked.area);
  const test::TestMesh annulus = test::flat_annulus(3, 12);
  EXPECT_THROW(prepare_chart_disk(annulus.V, annulus.F), TopologyError);
}

} // namespace
} // namespace iarap
