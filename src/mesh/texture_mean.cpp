#include "mesh/texture_mean.h"

#include <algorithm>
#include <array>
#include <csetjmp>
#include <cstdio>
#include <vector>

#include <jpeglib.h>
#include <png.h>

#include "core/srgb.h"

namespace radwalk {

namespace {

constexpr long kMaxPixels = 1L << 24;  // 4096 x 4096: 48 MB of 8-bit RGB at most

// linear_from_srgb of every 8-bit value.
const std::array<double, 256>& linear8() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int k = 0; k < 256; ++k) t[static_cast<std::size_t>(k)] = linear_from_srgb(k / 255.0);
    return t;
  }();
  return table;
}

// PNG through libpng's simplified API: every format converted to 8-bit sRGB RGB, read whole (bounded above).
TextureMean png_mean(std::string_view bytes) {
  TextureMean out;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    out.why = std::string("PNG: ") + image.message;
    return out;
  }
  out.width = image.width;
  out.height = image.height;
  if (static_cast<double>(image.width) * image.height > kMaxPixels) {
    png_image_free(&image);
    out.why = "PNG of " + std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels is too large";
    return out;
  }
  image.format = PNG_FORMAT_RGB;
  std::vector<png_byte> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) {
    out.why = std::string("PNG: ") + image.message;
    png_image_free(&image);
    return out;
  }
  Rgb sum = Rgb::Zero();
  const auto& lin = linear8();
  const std::size_t n = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t k = 0; k < n; ++k)
    for (int c = 0; c < 3; ++c) sum[c] += lin[pixels[3 * k + static_cast<std::size_t>(c)]];
  if (n > 0) out.mean = sum / static_cast<double>(n);
  else out.why = "PNG without pixels";
  return out;
}

struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_fail(j_common_ptr info) {
  auto* e = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, e->message);
  std::longjmp(e->jump, 1);
}

// JPEG through libjpeg, one scanline at a time, converted to RGB by the decoder.
TextureMean jpeg_mean(std::string_view bytes) {
  TextureMean out;
  jpeg_decompress_struct info{};
  JpegError error{};
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = jpeg_fail;
  error.manager.output_message = [](j_common_ptr) {};  // warnings are not printed
  // Everything that may be jumped over is declared before setjmp (no destructor is skipped).
  std::vector<JSAMPLE> row;
  Rgb sum = Rgb::Zero();
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&info);
    out.mean.reset();
    out.why = std::string("JPEG: ") + error.message;
    return out;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_RGB;
  out.width = info.image_width;
  out.height = info.image_height;
  if (static_cast<double>(info.image_width) * info.image_height > kMaxPixels) {
    jpeg_destroy_decompress(&info);
    out.why = "JPEG of " + std::to_string(out.width) + " x " + std::to_string(out.height) + " pixels is too large";
    return out;
  }
  jpeg_start_decompress(&info);
  row.resize(static_cast<std::size_t>(info.output_width) * static_cast<std::size_t>(info.output_components));
  const auto& lin = linear8();
  const int comps = info.output_components;
  while (info.output_scanline < info.output_height) {
    JSAMPROW rows[1] = {row.data()};
    jpeg_read_scanlines(&info, rows, 1);
    for (std::size_t x = 0; x < info.output_width; ++x)
      for (int c = 0; c < 3; ++c)
        sum[c] += lin[row[x * static_cast<std::size_t>(comps) + static_cast<std::size_t>(comps >= 3 ? c : 0)]];
  }
  const double n = static_cast<double>(info.output_width) * info.output_height;
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (n > 0) out.mean = sum / n;
  else out.why = "JPEG without pixels";
  return out;
}

}  // namespace

TextureMean texture_mean(std::string_view bytes) {
  static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::equal(bytes.begin(), bytes.begin() + 8, reinterpret_cast<const char*>(png_signature)))
    return png_mean(bytes);
  if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
      static_cast<unsigned char>(bytes[1]) == 0xD8 && static_cast<unsigned char>(bytes[2]) == 0xFF)
    return jpeg_mean(bytes);
  TextureMean out;
  out.why = "not a PNG or JPEG image (radwalk reads the mean colour of those two)";
  return out;
}

}  // namespace radwalk
