// Image output: sRGB encoding, PNG and EXR round trips, atomic writes.
#include <png.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/error.h"
#include "io/exr_writer.h"
#include "core/srgb.h"
#include "io/png_writer.h"

using namespace radwalk;
namespace fs = std::filesystem;

namespace {
RgbImage gradient(int w, int h) {
  RgbImage img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.at(x, y) = Rgb(x / double(w - 1), y / double(h - 1), 1.5 * (x + y) / (w + h));
  return img;
}
fs::path temp_dir() {
  const fs::path d = fs::temp_directory_path() / ("radwalk_pt_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("sRGB transfer function", "[image]") {
  CHECK(srgb_from_linear(0.0) == 0.0);
  CHECK(srgb_from_linear(1.0) == 1.0);
  CHECK(srgb_from_linear(2.0) == 1.0);
  CHECK(srgb_from_linear(-1.0) == 0.0);
  CHECK(srgb_from_linear(0.5) == Approx(0.735356983).epsilon(1e-8));
  // The two pieces meet at the threshold.
  CHECK(12.92 * 0.0031308 == Approx(1.055 * std::pow(0.0031308, 1 / 2.4) - 0.055).epsilon(1e-4));
  const auto bytes = to_srgb8(gradient(4, 3));
  CHECK(bytes.size() == 36);
  CHECK(bytes[0] == 0);
  CHECK(bytes[3 * 3] == 255);  // pixel (3, 0), red = 1
}

TEST_CASE("PNG round trip through libpng", "[image]") {
  const fs::path dir = temp_dir();
  const std::string path = (dir / "g.png").string();
  const RgbImage img = gradient(17, 9);
  write_png(path, img);
  png_image in;
  std::memset(&in, 0, sizeof in);
  in.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&in, path.c_str()));
  in.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> buf(PNG_IMAGE_SIZE(in));
  REQUIRE(png_image_finish_read(&in, nullptr, buf.data(), 0, nullptr));
  CHECK(in.width == 17);
  CHECK(in.height == 9);
  CHECK(buf == to_srgb8(img));
  // Only the final file remains (atomic write leaves no temporary).
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  CHECK_THROWS_AS(write_png((dir / "missing" / "x.png").string(), img), InputError);
  fs::remove_all(dir);
}

TEST_CASE("EXR round trip: float exact, half within half precision", "[image]") {
  const fs::path dir = temp_dir();
  RgbImage img = gradient(13, 7);
  img.at(2, 3) = Rgb(1234.5, 1e-3, 0.0);
  write_exr((dir / "f.exr").string(), img, ExrPixelType::float32);
  write_exr((dir / "h.exr").string(), img, ExrPixelType::half);
  const RgbImage f = read_exr((dir / "f.exr").string());
  const RgbImage h = read_exr((dir / "h.exr").string());
  REQUIRE(f.width == 13);
  REQUIRE(f.height == 7);
  for (std::size_t k = 0; k < img.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      CHECK(f.pixels[k][c] == static_cast<float>(img.pixels[k][c]));
      CHECK(std::abs(h.pixels[k][c] - img.pixels[k][c]) <= std::abs(img.pixels[k][c]) * 0x1p-11 + 1e-7);
    }
  CHECK_THROWS_AS(read_exr((dir / "none.exr").string()), InputError);
  fs::remove_all(dir);
}
