#pragma once
// The mean colour of a texture image, as a diffuse reflectance: what a material's `map_Kd` texture contributes to
// its rho when the radiosity solvers take one rho per material (mtl.h, "Textures").
//
// The pixels are 8- or 16-bit sRGB (PNG through libpng, JPEG through libjpeg, Debian's libpng-dev and
// libjpeg62-turbo-dev); each channel is decoded to linear reflectance (core/srgb.h linear_from_srgb) before the
// mean, because reflectance adds in linear light: the mean of a half-black, half-white texture is 0.5, not the
// 0.214 of its mean sRGB value 0.5. Grey images give equal channels; alpha is ignored (a cut-out's transparent
// pixels count as their colour). The mean is over every pixel (a texture maps uniformly to the surface as far as
// radwalk knows: the uv mapping is not read).
#include <optional>
#include <string>
#include <string_view>

#include "core/types.h"

namespace radwalk {

struct TextureMean {
  std::optional<Rgb> mean;  // the mean linear reflectance per channel; empty if the image cannot be read
  long width = 0, height = 0;
  std::string why;          // why it cannot be read ("not a PNG or JPEG image", the decoder's message)
};

// The mean of the image in `bytes` (PNG or JPEG, by their signatures). Never throws for bad bytes: `why` says
// what is wrong. Images above 2^24 pixels (4096 x 4096) are not read (bounded memory: a PNG is decoded whole,
// 3 bytes a pixel; a JPEG a row at a time), so a hostile header cannot make the reader allocate gigabytes.
TextureMean texture_mean(std::string_view bytes);

}  // namespace radwalk
