#pragma once
// Basic numeric types shared by every layer.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace radwalk {

using Vec3 = Eigen::Vector3d;   // a point or direction, in the mesh's length unit
using Rgb = Eigen::Array3d;     // one value per colour channel (r, g, b)
using PatchIndex = std::int32_t;

// Radiosity or any per-patch RGB field: one row per patch, columns r, g, b.
using PatchRgb = Eigen::Array<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInvPi = 1.0 / kPi;

}  // namespace radwalk
