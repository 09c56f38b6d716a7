#pragma once
// OpenEXR output of a linear RGB image (channels R, G, B; scanlines, ZIP compression), in half or 32-bit float.
// Values are stored as they are (no exposure, no clamping): radiance in W / (m^2 sr) for rendered images, the
// standard error for an error image. Written atomically; throws InputError when the file cannot be written.
// run_id: when not empty, the header's string attribute "run_id" (apps/run_metadata.h).
#include <string>

#include "core/image.h"

namespace radwalk {

enum class ExrPixelType { half, float32 };

void write_exr(const std::string& path, const RgbImage& image, ExrPixelType type = ExrPixelType::float32,
               const std::string& run_id = "");

// The header attribute "run_id" of an EXR file, "" when it has none (for tests and tools).
std::string read_exr_run_id(const std::string& path);

// Reads R, G, B of an EXR written by write_exr (for tests and tools), as float.
RgbImage read_exr(const std::string& path);

}  // namespace radwalk
