#pragma once
// RayPacket: up to kPacketSize rays in single precision as a structure of arrays, the form in which Embree
// traces a packet (rtcIntersect16). For callers that make many rays at once (the random walks' ray kernel):
// they write the lanes directly, with no Ray (double) per ray to build and round to float on the way to the
// tracer.
//
// Lanes [0, count) are the rays; later lanes are ignored. Directions should be unit length (Hit::t is then a
// distance); tmax as Ray::tmax. Ray <-> lane conversion: set(k, ray) rounds to float (a tmax beyond the float
// range becomes infinity), ray(k) widens to double exactly.
#include <cstddef>
#include <limits>

#include "visibility/visibility.h"

namespace radwalk {

inline constexpr std::size_t kPacketSize = 16;

// tmax in single precision: beyond the largest float it is infinity (the conversion would be undefined).
inline float to_float_tmax(double tmax) {
  return tmax >= double(std::numeric_limits<float>::max()) ? std::numeric_limits<float>::infinity()
                                                           : float(tmax);
}

struct RayPacket {
  std::size_t count = 0;
  alignas(64) float org_x[kPacketSize];
  alignas(64) float org_y[kPacketSize];
  alignas(64) float org_z[kPacketSize];
  alignas(64) float dir_x[kPacketSize];
  alignas(64) float dir_y[kPacketSize];
  alignas(64) float dir_z[kPacketSize];
  alignas(64) float tmax[kPacketSize];

  void set(std::size_t k, const Ray& ray) {
    org_x[k] = float(ray.origin.x());
    org_y[k] = float(ray.origin.y());
    org_z[k] = float(ray.origin.z());
    dir_x[k] = float(ray.direction.x());
    dir_y[k] = float(ray.direction.y());
    dir_z[k] = float(ray.direction.z());
    tmax[k] = to_float_tmax(ray.tmax);
  }
  Ray ray(std::size_t k) const {
    Ray r;
    r.origin = Vec3(org_x[k], org_y[k], org_z[k]);
    r.direction = Vec3(dir_x[k], dir_y[k], dir_z[k]);
    r.tmax = tmax[k];
    return r;
  }
};

}  // namespace radwalk
