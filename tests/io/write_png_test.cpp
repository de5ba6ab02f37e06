// write_png: the bytes read back by libpng equal the image; bad images and paths are refused by name.
#include "iarap/io/write_png.h"

#include "iarap/core/errors.h"
#include "io/png_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

iarap::RgbImage gradient(int width, int height) {
  iarap::RgbImage image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 3; ++k)
        image.rgb.push_back(static_cast<std::uint8_t>((37 * x + 91 * y + 70 * k) % 256));
  return image;
}

TEST(WritePng, ReadsBackTheSamePixels) {
  const auto dir = iarap::test::temp_dir("write_png");
  const iarap::RgbImage image = gradient(7, 5);
  iarap::write_png((dir / "a.PNG").string(), image);
  const iarap::RgbImage back = iarap::test::read_png_rgb((dir / "a.PNG").string());
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, image.rgb);
  // No temporary file left beside it.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
  EXPECT_EQ(files, 1);
  fs::remove_all(dir);
}

TEST(WritePng, RefusesBadImagesAndPathsByName) {
  const auto dir = iarap::test::temp_dir("write_png_errors");
  const std::string path = (dir / "b.png").string();
  iarap::RgbImage short_image = gradient(4, 4);
  short_image.rgb.pop_back();
  const struct {
    std::string path;
    iarap::RgbImage image;
    std::string says;
  } cases[] = {
      {(dir / "b.jpg").string(), gradient(2, 2), "b.jpg: cannot write an image as '.jpg'"},
      {path, iarap::RgbImage{}, "b.png: cannot write an empty image (0 x 0 pixels)"},
      {path, short_image, "needs 48 bytes; got 47"},
      {(dir / "missing" / "c.png").string(), gradient(2, 2), "c.png: cannot create a temporary file"},
  };
  for (const auto& c : cases) {
    try {
      iarap::write_png(c.path, c.image);
      ADD_FAILURE() << c.path << " was written";
    } catch (const iarap::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(fs::exists(path));
  fs::remove_all(dir);
}

} // namespace
