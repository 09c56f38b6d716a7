#include "io/png_writer.h"

#include <png.h>
#include <zlib.h>

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

namespace {

void put_u32(std::string& s, std::uint32_t v) {
  for (int k = 3; k >= 0; --k) s += static_cast<char>((v >> (8 * k)) & 0xff);
}

std::uint32_t get_u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

// A PNG chunk: length (big-endian), type, data, CRC-32 of type and data (PNG specification, section 5.3).
std::string png_chunk(const std::string& type, const std::string& data) {
  std::string chunk;
  put_u32(chunk, static_cast<std::uint32_t>(data.size()));
  const std::string body = type + data;
  chunk += body;
  put_u32(chunk, static_cast<std::uint32_t>(
                     crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  return chunk;
}

constexpr std::size_t kSignatureBytes = 8, kIhdrChunkBytes = 4 + 4 + 13 + 4;

}  // namespace

std::string png_text(const std::string& png, const std::string& keyword) {
  std::size_t at = kSignatureBytes;
  while (at + 12 <= png.size()) {
    const std::uint32_t length = get_u32(png, at);
    if (length > png.size() - at - 12) break;
    if (png.compare(at + 4, 4, "tEXt") == 0) {
      const std::string data = png.substr(at + 8, length);
      const std::size_t nul = data.find('\0');
      if (nul != std::string::npos && data.compare(0, nul, keyword) == 0) return data.substr(nul + 1);
    }
    at += 12 + length;
  }
  return "";
}

void write_png(const std::string& path, const RgbImage& image, double exposure, const std::string& run_id) {
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
  std::string text;
  // tEXt after IHDR (libpng's simplified API writes none): keyword, a NUL, the Latin-1 text.
  if (!run_id.empty()) text = png_chunk("tEXt", std::string("run_id") + '\0' + run_id);
  const std::size_t head = std::min(encoded.size(), kSignatureBytes + kIhdrChunkBytes);
  write_atomically(path, [&](std::ostream& out) {
    out.write(encoded.data(), static_cast<std::streamsize>(head));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.write(encoded.data() + head, static_cast<std::streamsize>(encoded.size() - head));
  });
}

}  // namespace radwalk
