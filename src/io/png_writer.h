#pragma once
// PNG output of a linear RGB image: 8-bit sRGB, after scaling by `exposure` and clamping to [0, 1].
// sRGB encoding (IEC 61966-2-1): c' = 12.92 c for c <= 0.0031308, else 1.055 c^(1/2.4) - 0.055; rounded to
// 0..255. The file is written atomically (core/atomic_write.h). Throws InputError when it cannot be written.
// run_id: when not empty, a tEXt chunk with keyword "run_id" right after IHDR (apps/run_metadata.h).
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace radwalk {

// 8-bit sRGB bytes, row-major RGB, row 0 at the top (what write_png stores).
std::vector<std::uint8_t> to_srgb8(const RgbImage& image, double exposure = 1.0);

void write_png(const std::string& path, const RgbImage& image, double exposure = 1.0, const std::string& run_id = "");

// The text of the tEXt chunk with keyword `keyword` in PNG bytes, "" when there is none (for tests and tools).
std::string png_text(const std::string& png_bytes, const std::string& keyword);

}  // namespace radwalk
