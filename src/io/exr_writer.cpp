#include "io/exr_writer.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include <exception>
#include <vector>

#include "core/atomic_write.h"
#include "core/error.h"

namespace radwalk {

namespace {
// Planar channel buffers, then one Slice per channel (xStride = one element, yStride = one row).
template <class T>
void write_planes(const std::string& tmp_path, const RgbImage& image, Imf::PixelType type, const std::string& run_id) {
  const std::size_t n = image.pixels.size();
  std::vector<T> planes[3];
  for (int c = 0; c < 3; ++c) {
    planes[c].resize(n);
    for (std::size_t k = 0; k < n; ++k) planes[c][k] = static_cast<T>(static_cast<float>(image.pixels[k][c]));
  }
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  if (!run_id.empty()) header.insert("run_id", Imf::StringAttribute(run_id));
  const char* names[3] = {"R", "G", "B"};
  Imf::FrameBuffer fb;
  for (int c = 0; c < 3; ++c) {
    header.channels().insert(names[c], Imf::Channel(type));
    fb.insert(names[c], Imf::Slice(type, reinterpret_cast<char*>(planes[c].data()), sizeof(T),
                                   sizeof(T) * static_cast<std::size_t>(image.width)));
  }
  Imf::OutputFile file(tmp_path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(image.height);
}
}  // namespace

void write_exr(const std::string& path, const RgbImage& image, ExrPixelType type, const std::string& run_id) {
  if (image.width <= 0 || image.height <= 0) throw InputError(path + ": cannot write an empty image");
  write_atomically_via_path(path, [&](const std::string& tmp) {
    try {
      if (type == ExrPixelType::half)
        write_planes<half>(tmp, image, Imf::HALF, run_id);
      else
        write_planes<float>(tmp, image, Imf::FLOAT, run_id);
    } catch (const std::exception& e) {
      throw InputError(path + ": cannot write EXR: " + e.what());
    }
  });
}

std::string read_exr_run_id(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const auto* id = file.header().findTypedAttribute<Imf::StringAttribute>("run_id");
    return id ? id->value() : std::string();
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot read EXR: " + e.what());
  }
}

RgbImage read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    std::vector<float> planes[3];
    const char* names[3] = {"R", "G", "B"};
    Imf::FrameBuffer fb;
    for (int c = 0; c < 3; ++c) {
      planes[c].assign(static_cast<std::size_t>(w) * h, 0.0f);
      // Slice base pointer is offset so that (dw.min.x, dw.min.y) lands on element 0.
      char* base = reinterpret_cast<char*>(planes[c].data()) -
                   (static_cast<std::ptrdiff_t>(dw.min.x) + static_cast<std::ptrdiff_t>(dw.min.y) * w) *
                       static_cast<std::ptrdiff_t>(sizeof(float));
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * static_cast<std::size_t>(w)));
    }
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    RgbImage image(w, h);
    for (std::size_t k = 0; k < image.pixels.size(); ++k) image.pixels[k] = Rgb(planes[0][k], planes[1][k], planes[2][k]);
    return image;
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot read EXR: " + e.what());
  }
}

}  // namespace radwalk
