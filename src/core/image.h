#pragma once
// RgbImage: a linear RGB image (row 0 at the top), one Rgb per pixel, in the unit of what it holds (radiance,
// W / (m^2 sr), for rendered images; its standard error for the error image).
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

}  // namespace radwalk
