#pragma once
// RgbImage: a linear RGB image (row 0 at the top), one Rgb per pixel, in the unit of what it holds (radiance,
// W / (m^2 sr), for rendered images; its standard error for the error image).
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace radwalk {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  // row-major, size width * height

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, Rgb::Zero()) {}
  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
  // Mean over all pixels and channels' mean (for summaries).
  Rgb mean() const;
};

// Images hold a mean and a standard error of 3 doubles per pixel (48 bytes), and the writers and the light
// tracer's tallies more: at most 2^26 pixels (8192 x 8192, 3.2 GB for the two images).
constexpr std::uint64_t kMaxImagePixels = std::uint64_t{1} << 26;
constexpr std::uint64_t kImageBytesPerPixel = 2 * 3 * sizeof(double);

// Throws InputError unless width >= 1, height >= 1 and width x height <= kMaxImagePixels; the message starts with
// `what` (how the caller's user wrote the size, e.g. "--width 9000 --height 9000") and states the bytes the size
// would need. Called before anything is computed.
void check_image_size(std::int64_t width, std::int64_t height, const std::string& what);

}  // namespace radwalk
