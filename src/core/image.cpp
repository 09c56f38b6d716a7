#include "core/image.h"

namespace radwalk {

Rgb RgbImage::mean() const {
  Rgb s = Rgb::Zero();
  for (const auto& p : pixels) s += p;
  return pixels.empty() ? s : Rgb(s / static_cast<double>(pixels.size()));
}

}  // namespace radwalk
