// libpng rather than a hand-written encoder: it is the reference implementation every viewer reads, and
// its simplified API (png_image_write_to_memory) needs no setjmp.
#include "iarap/io/write_png.h"

#include "atomic_file.h"
#include "file_extension.h"

#include "iarap/core/errors.h"

#include <png.h>

#include <cstring>

namespace iarap {

namespace {

void check_image(const std::string& path, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0)
    throw InputError(path + ": cannot write an empty image (" + std::to_string(image.width) + " x " +
                     std::to_string(image.height) + " pixels)");
  const std::size_t expected =
      3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.rgb.size() != expected)
    throw InputError(path + ": an RGB image of " + std::to_string(image.width) + " x " +
                     std::to_string(image.height) + " pixels needs " + std::to_string(expected) +
                     " bytes; got " + std::to_string(image.rgb.size()));
}

} // namespace

void write_png(const std::string& path, const RgbImage& image) {
  const std::string extension = io_detail::lower_extension(path);
  if (extension != ".png")
    throw InputError(path + ": cannot write an image as '" + extension + "'; use .png");
  check_image(path, image);
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const png_int_32 stride = 3 * image.width;
  // First call: the encoded size; second: the bytes.
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), stride, nullptr))
    throw InputError(path + ": libpng cannot encode the image: " + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), stride, nullptr))
    throw InputError(path + ": libpng cannot encode the image: " + png.message);
  bytes.resize(size);
  png_image_free(&png);
  io_detail::write_file_atomically(path, bytes);
}

} // namespace iarap
