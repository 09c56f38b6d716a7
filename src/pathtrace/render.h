#pragma once
// render_image: a path-traced linear RGB image of the patches seen by a pinhole camera.
//
// Pixel (px, py) = (1/spp) sum_s L(ray through (px + u, py + v)), (u, v) uniform in [0, 1)^2 (box filter):
// the mean radiance over the pixel (W / (m^2 sr)). The per-pixel standard error is sqrt(var / spp) with the
// unbiased per-sample variance. Sample s of pixel p = py * width + px uses the stream (seed, render_pixel, p, s) (core/rng.h): the image is
// bit-identical for any thread count.
#include <cstdint>

#include "core/image.h"
#include "pathtrace/camera.h"
#include "pathtrace/integrator.h"

namespace radwalk {

struct PatchSet;

struct RenderOptions {
  int width = 256;
  int height = 256;
  long spp = 64;  // samples per pixel, >= 2
  std::uint64_t seed = 1;
  IntegratorOptions integrator;
  bool progress = true;
};

struct RenderResult {
  RgbImage mean;  // radiance per pixel
  RgbImage se;    // standard error per pixel and channel
  long spp = 0;
  long rays = 0;      // all rays traced (camera, continuation and shadow rays)
  long vertices = 0;  // scattering events
  double seconds = 0;
};

RenderResult render_image(const PatchSet& patches, const Visibility& visibility, const Camera& camera,
                          const RenderOptions& options);

}  // namespace radwalk
