#pragma once
// The sRGB transfer function (IEC 61966-2-1) from linear light to display values, the one mapping every radwalk
// display output uses (the path tracer's PNG, the B_srgb array of the .vtp files, the ParaView renders):
//   c' = 12.92 c                  for c <= 0.0031308
//   c' = 1.055 c^(1/2.4) - 0.055  otherwise,
// after clamping c to [0, 1] (NaN counts as 0). 8-bit values are round(255 c').
// Radiosity B (W/m^2) is shown as its radiance B / pi times an exposure (1 by default): display_linear(B) =
// exposure * B / pi, so a white Lambertian patch of radiance 1 is full white.
#include <cmath>
#include <cstdint>

#include "core/types.h"

namespace radwalk {

// sRGB-encoded value in [0, 1] of linear c (clamped to [0, 1]).
inline double srgb_from_linear(double c) {
  if (!(c > 0)) return 0.0;  // also maps NaN to black
  if (c >= 1) return 1.0;
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// Linear value of an sRGB-encoded c' in [0, 1] (clamped), the inverse of srgb_from_linear:
//   c = c' / 12.92 for c' <= 0.04045, ((c' + 0.055) / 1.055)^2.4 otherwise.
inline double linear_from_srgb(double c) {
  if (!(c > 0)) return 0.0;
  if (c >= 1) return 1.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// The same as an 8-bit value, round(255 srgb_from_linear(c)).
inline std::uint8_t srgb8_from_linear(double c) {
  return static_cast<std::uint8_t>(std::lround(255.0 * srgb_from_linear(c)));
}

// The 8-bit display colour of a radiosity B (W/m^2): srgb8_from_linear(exposure * B / pi).
inline std::uint8_t srgb8_from_radiosity(double B, double exposure = 1.0) {
  return srgb8_from_linear(exposure * B * kInvPi);
}

}  // namespace radwalk
