// render_uv_picture on a flat disk mapped to itself: both checkerboard colours inside the layout, white
// around it, the textured disk shaded by the Lambert factor the header's light gives a face seen head on,
// flipped triangles red in both halves and only when there are some.
#include "iarap/param/render_uv_picture.h"

#include "iarap/core/errors.h"
#include "param/disk_meshes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace {

using iarap::RgbImage;
using iarap::UvPictureColours;

std::array<int, 3> pixel(const RgbImage& image, int x, int y) {
  const std::size_t at = 3 * (static_cast<std::size_t>(y) * image.width + x);
  return {image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]};
}

std::array<int, 3> scaled(const std::uint8_t (&c)[3], double factor) {
  return {static_cast<int>(std::lround(c[0] * factor)), static_cast<int>(std::lround(c[1] * factor)),
          static_cast<int>(std::lround(c[2] * factor))};
}

// Pixels of colour c in columns [x0, x1).
int count(const RgbImage& image, int x0, int x1, const std::array<int, 3>& c) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = x0; x < x1; ++x) n += pixel(image, x, y) == c;
  return n;
}

iarap::UvPictureOptions small_picture() {
  iarap::UvPictureOptions options;
  options.height = 96;
  options.checker_squares = 4;
  options.supersample = 1; // sample colours unblended, so they compare exactly
  return options;
}

TEST(RenderUvPicture, DiskMappedToItself) {
  const iarap::test::TestMesh disk = iarap::test::flat_disk(6, 24);
  const Eigen::MatrixXd UV = disk.V.leftCols(2);
  const RgbImage image = iarap::render_uv_picture(disk.V, disk.F, UV, small_picture());
  ASSERT_EQ(image.width, 192);
  ASSERT_EQ(image.height, 96);
  ASSERT_EQ(image.rgb.size(), 3u * 192 * 96);
  const int h = image.height;
  const auto background = scaled(UvPictureColours::background, 1);
  // Corners of both halves are outside the disk.
  for (const int x : {0, h - 1, h, 2 * h - 1})
    for (const int y : {0, h - 1}) EXPECT_EQ(pixel(image, x, y), background) << x << ", " << y;
  // The UV half: both checkerboard colours, no red.
  EXPECT_GT(count(image, 0, h, scaled(UvPictureColours::light, 1)), h * h / 20);
  EXPECT_GT(count(image, 0, h, scaled(UvPictureColours::dark, 1)), h * h / 20);
  EXPECT_EQ(count(image, 0, 2 * h, scaled(UvPictureColours::flipped, 1)), 0);
  // The textured half: the disk faces the eye (its normal is +z), light (0.25, 0.35, 1) normalized, so
  // every face has Lambert factor 0.22 + 0.78 / |(0.25, 0.35, 1)|.
  const double lambert = 0.22 + 0.78 / std::sqrt(0.25 * 0.25 + 0.35 * 0.35 + 1);
  const int light = count(image, h, 2 * h, scaled(UvPictureColours::light, lambert));
  const int dark = count(image, h, 2 * h, scaled(UvPictureColours::dark, lambert));
  EXPECT_GT(light, h * h / 20);
  EXPECT_GT(dark, h * h / 20);
  // The same disk, the same fit (92% of the square): both halves covered alike, the 24-gon's area
  // 0.9886 pi / 4 x 0.92^2 = 0.657 of the square.
  const auto background_count = [&](int x0) { return count(image, x0, x0 + h, background); };
  EXPECT_NEAR(1 - double(background_count(0)) / (h * h), 0.657, 0.03);
  EXPECT_NEAR(1 - double(background_count(h)) / (h * h), 0.657, 0.03);
}

TEST(RenderUvPicture, FlippedTrianglesAreRed) {
  const iarap::test::TestMesh disk = iarap::test::flat_disk(4, 16);
  Eigen::MatrixXd UV = disk.V.leftCols(2);
  UV.row(0) << 0.6, 0.1; // the centre beyond its ring: the fan triangles on the far side turn clockwise
  int flipped = 0;
  for (Eigen::Index f = 0; f < disk.F.rows(); ++f) {
    const Eigen::Vector2d a = UV.row(disk.F(f, 0)), b = UV.row(disk.F(f, 1)), c = UV.row(disk.F(f, 2));
    flipped += (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0;
  }
  ASSERT_GT(flipped, 0);
  iarap::UvPictureOptions options = small_picture();
  options.height = 256;
  const RgbImage image = iarap::render_uv_picture(disk.V, disk.F, UV, options);
  const int h = image.height;
  EXPECT_GT(count(image, 0, h, scaled(UvPictureColours::flipped, 1)), 20);
  const double lambert = 0.22 + 0.78 / std::sqrt(0.25 * 0.25 + 0.35 * 0.35 + 1);
  EXPECT_GT(count(image, h, 2 * h, scaled(UvPictureColours::flipped, lambert)), 20);
}

TEST(RenderUvPicture, SurfaceSeenFromItsFront) {
  // The disk in the xz plane, facing -y: the view turns to it, so the right half is mostly covered.
  iarap::test::TestMesh disk = iarap::test::flat_disk(4, 16);
  const Eigen::MatrixXd UV = disk.V.leftCols(2);
  disk.V.col(2) = disk.V.col(1);
  disk.V.col(1).setZero();
  const RgbImage image = iarap::render_uv_picture(disk.V, disk.F, UV, small_picture());
  const int h = image.height;
  const int background = count(image, h, 2 * h, scaled(UvPictureColours::background, 1));
  // A disk of diameter 0.92 h in an h x h square covers pi / 4 * 0.92^2 = 66% of it.
  EXPECT_NEAR(1 - double(background) / (h * h), 0.66, 0.05);
}

TEST(RenderUvPicture, BadInputIsNamed) {
  const iarap::test::TestMesh disk = iarap::test::flat_disk(2, 8);
  const Eigen::MatrixXd UV = disk.V.leftCols(2);
  const auto says = [&](const Eigen::MatrixXd& uv, const iarap::UvPictureOptions& options,
                        const std::string& text) {
    try {
      iarap::render_uv_picture(disk.V, disk.F, uv, options);
      ADD_FAILURE() << "no error; expected " << text;
    } catch (const iarap::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  says(UV.topRows(3), {}, "UV must be #V x 2 = 17 x 2; got 3 x 2");
  Eigen::MatrixXd nan = UV;
  nan(5, 1) = NAN;
  says(nan, {}, "vertex 5 has a coordinate that is not finite (UV)");
  says(Eigen::MatrixXd::Zero(UV.rows(), 2), {}, "no extent");
  iarap::UvPictureOptions tiny;
  tiny.height = 4;
  says(UV, tiny, "height must be in [16, 8192]; got 4");
  iarap::UvPictureOptions coarse;
  coarse.supersample = 9;
  says(UV, coarse, "supersample must be in [1, 4]; got 9");
}

} // namespace
