#include "core/image.h"

#include "core/error.h"

namespace radwalk {

Rgb RgbImage::mean() const {
  Rgb s = Rgb::Zero();
  for (const auto& p : pixels) s += p;
  return pixels.empty() ? s : Rgb(s / static_cast<double>(pixels.size()));
}

void check_image_size(std::int64_t width, std::int64_t height, const std::string& what) {
  if (width < 1 || height < 1) throw InputError(what + ": an image needs a width and a height of at least 1 pixel");
  // Both are at least 1, so the product is checked against the limit without overflowing.
  if (width <= static_cast<std::int64_t>(kMaxImagePixels) && height <= static_cast<std::int64_t>(kMaxImagePixels) &&
      std::uint64_t(width) * std::uint64_t(height) <= kMaxImagePixels)
    return;
  const long double pixels = static_cast<long double>(width) * static_cast<long double>(height);
  const auto text = [](long double x) {
    return x < 1.8e19L ? std::to_string(static_cast<std::uint64_t>(x)) : number_text(static_cast<double>(x));
  };
  throw InputError(what + ": " + text(pixels) + " pixels would need at least " +
                   text(pixels * static_cast<long double>(kImageBytesPerPixel)) + " bytes (" +
                   std::to_string(kImageBytesPerPixel) + " per pixel for the image and its standard error); at most " +
                   std::to_string(kMaxImagePixels) + " pixels (e.g. 8192 x 8192)");
}

}  // namespace radwalk
