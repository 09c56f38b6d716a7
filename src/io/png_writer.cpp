#include "io/png_writer.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ostream>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/srgb.h"

namespace radwalk {

std::vector<std::uint8_t> to_srgb8(const RgbImage& image, double exposure) {
  std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
  for (std::size_t k = 0; k < image.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c)
      bytes[3 * k + c] = srgb8_from_linear(exposure * image.pixels[k][c]);  // the one sRGB mapping (core/srgb.h)
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
