// Writing an 8-bit RGB image as a PNG file (libpng), atomically.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace iarap {

// An 8-bit RGB image: rows from the top, pixels left to right, three bytes (r, g, b) per pixel, so
// pixel (x, y) starts at rgb[3 * (y * width + x)].
struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb; // 3 * width * height bytes
};

// Encodes `image` as a PNG (libpng's simplified API) and writes it to `path` atomically (a temporary file
// renamed over `path`). Throws InputError naming the path when the extension is not .png (any case), the
// image is empty or its rgb size is not 3 * width * height, libpng fails (its message) or the file cannot
// be written.
void write_png(const std::string& path, const RgbImage& image);

} // namespace iarap
