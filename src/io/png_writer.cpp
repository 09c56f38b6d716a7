#include "io/png_writer.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ostream>

#include "core/atomic_write.h"
#include "core/error.h"

namespace radwalk {

double srgb_encode(double c) {
  if (!(c > 0)) return 0.0;  // also maps NaN to black
  if (c >= 1) return 1.0;
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

std::vector<std::uint8_t> to_srgb8(const RgbImage& image, double exposure) {
  std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
  for (std::size_t k = 0; k < image.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c)
      bytes[3 * k + c] = static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(exposure * image.pixels[k][c])));
  return bytes;
}

void write_png(const std::string& path, const RgbImage& image, double exposure) {
  if (image.width <= 0 || image.height <= 0) throw InputError(path + ": cannot write an empty image");
  const std::vector<std::uint8_t> bytes = to_srgb8(image, exposure);

  // Encode in memory with libpng's simplified API (no setjmp error handling needed), then write atomically.
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  if (!png_image_write_get_memory_size(png, size, 0, bytes.data(), 0, nullptr))
    throw InputError(path + ": PNG encoding failed: " + png.message);
  std::vector<char> encoded(size);
  if (!png_image_write_to_memory(&png, encoded.data(), &size, 0, bytes.data(), 0, nullptr))
    throw InputError(path + ": PNG encoding failed: " + png.message);
  encoded.resize(size);
  write_atomically(path, [&](std::ostream& out) { out.write(encoded.data(), static_cast<std::streamsize>(size)); });
}

}  // namespace radwalk
