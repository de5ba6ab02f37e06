// Reading a PNG back for the tests (libpng's simplified API), as an 8-bit RGB image.
#pragma once
#include "iarap/io/write_png.h"

#include <png.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace iarap::test {

inline RgbImage read_png_rgb(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
    throw std::runtime_error(path + ": " + png.message);
  png.format = PNG_FORMAT_RGB;
  RgbImage image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr))
    throw std::runtime_error(path + ": " + png.message);
  return image;
}

} // namespace iarap::test
