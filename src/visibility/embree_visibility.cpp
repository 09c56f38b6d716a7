#include "visibility/embree_visibility.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>

#include "core/check.h"
#include "core/error.h"
#include "patch/contact_pairs.h"
#include "visibility/ray_packet.h"

namespace radwalk {

struct EmbreeVisibility::Device {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::mutex mutex;
  std::string error;  // first error reported by the callback, empty when none

  ~Device() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  // Throws the first error the callback recorded (or rtcGetDeviceError's code) after `step`.
  void check(const char* step) {
    const RTCError code = rtcGetDeviceError(device);
    std::lock_guard lock(mutex);
    if (!error.empty() || code != RTC_ERROR_NONE)
      throw std::runtime_error("embree: " + std::string(step) + ": " +
                               (error.empty() ? "error code " + std::to_string(int(code)) : error));
  }
};

namespace {

void record_error(void* user, RTCError code, const char* message) {
  auto* d = static_cast<EmbreeVisibility::Device*>(user);
  std::lock_guard lock(d->mutex);
  if (d->error.empty()) d->error = std::string(message ? message : "") + " (code " + std::to_string(int(code)) + ")";
}

// The Embree ray of `ray` (single precision, tnear 0), with id `id`.
RTCRay rtc_ray(const Ray& ray, unsigned id) {
  RTCRay r;
  r.org_x = float(ray.origin.x());
  r.org_y = float(ray.origin.y());
  r.org_z = float(ray.origin.z());
  r.dir_x = float(ray.direction.x());
  r.dir_y = float(ray.direction.y());
  r.dir_z = float(ray.direction.z());
  r.tnear = 0.0f;
  r.tfar = to_float_tmax(ray.tmax);
  r.time = 0.0f;
  r.mask = ~0u;
  r.id = id;
  r.flags = 0;
  return r;
}

// Lanes [0, m) of `src` into `dst`, and lane 0 again into the lanes [m, 16) that are masked off, so that
// Embree never reads an uninitialised value (0 < m <= 16). All 16 are copied first: one fixed-size copy.
void copy_lanes(float* dst, const float* src, std::size_t m) {
  std::memcpy(dst, src, 16 * sizeof(float));
  std::fill(dst + m, dst + 16, src[0]);
}

void validate(const PatchSet& patches) {
  const std::size_t n = patches.size();
  RADWALK_CHECK_EQ(patches.corners.size(), n);  // the arrays of a PatchSet are built together
  RADWALK_CHECK_EQ(patches.normal.size(), n);
  for (std::size_t p = 0; p < patches.points.size(); ++p)
    if (!patches.points[p].allFinite())
      throw InputError(locate(patches.source, 0, -1, "point " + std::to_string(p) + " is not finite"));
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < patches.corner_count(i); ++k) {
      const auto c = patches.corners[i][k];
      if (c < 0 || std::size_t(c) >= patches.points.size())
        throw InputError(locate(patches.source, 0, long(patches.face.size() > i ? patches.face[i] : long(i)),
                                "corner index " + std::to_string(c) + " out of range"));
    }
}

// The intersection filter of the filtered geometries: a hit is rejected when it arrives at a side its patch
// rejects (EmbreeVisibility::kRejectBack, kRejectFront), the side told by dot(direction, normal) < 0 in the float
// arithmetic of Hit::front, so that traversal goes on to the coincident patch that takes the hit.
void reject_hits(const RTCFilterFunctionNArguments* args) {
  const auto* prims = static_cast<const EmbreeVisibility::Primitives*>(args->geometryUserPtr);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] != -1) continue;
    const auto patch = std::size_t(prims->patch[RTCHitN_primID(args->hit, args->N, k)]);
    const Eigen::Vector3f& n = (*prims->normal)[patch];
    const float dx = RTCRayN_dir_x(args->ray, args->N, k), dy = RTCRayN_dir_y(args->ray, args->N, k),
                dz = RTCRayN_dir_z(args->ray, args->N, k);
    const bool front = dx * n.x() + dy * n.y() + dz * n.z() < 0.0f;
    if ((*prims->reject)[patch] & (front ? EmbreeVisibility::kRejectFront : EmbreeVisibility::kRejectBack))
      args->valid[k] = 0;
  }
}

}  // namespace

EmbreeVisibility::EmbreeVisibility(const PatchSet& patches, const EmbreeOptions& options)
    : device_(std::make_unique<Device>()) {
  validate(patches);
  // Step 1: device, with errors recorded by the callback and rethrown by check().
  device_->device = rtcNewDevice(options.device_config.c_str());
  if (!device_->device)
    throw std::runtime_error("embree: rtcNewDevice(\"" + options.device_config + "\") failed with code " +
                             std::to_string(int(rtcGetDeviceError(nullptr))));
  rtcSetDeviceErrorFunction(device_->device, record_error, device_.get());

  // Step 2: the scene.
  device_->scene = rtcNewScene(device_->device);
  rtcSetSceneFlags(device_->scene, options.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  device_->check("scene");

  // Step 3: split patches into triangles and quads, remembering each primitive's patch; the patches that reject
  // a side (two-sided faces: the back; contact pairs: the front) go into the filtered geometries.
  const std::size_t n = patches.size();
  normal_.resize(n);
  reject_.assign(n, 0);
  const std::vector<std::int32_t> pair = contact_pair_ids(patches);
  for (std::size_t i = 0; i < n; ++i) {
    normal_[i] = patches.normal[i].cast<float>();
    if (patches.two_sided(i)) reject_[i] |= kRejectBack;
    if (pair[i] >= 0) reject_[i] |= kRejectFront;
    primitives_[(reject_[i] ? 2 : 0) + (patches.is_quad(i) ? 1 : 0)].patch.push_back(PatchIndex(i));
  }
  if (!primitives_[2].patch.empty() || !primitives_[3].patch.empty()) {
    if (!rtcGetDeviceProperty(device_->device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
      throw std::runtime_error("embree: this Embree has no filter functions, which two-sided faces and contact "
                               "pairs need");
  }

  // Step 4: one geometry per primitive kind, both over all points (float copies made by Embree buffers).
  auto add_geometry = [&](RTCGeometryType type, Primitives& primitives, bool filtered) -> unsigned {
    const std::vector<PatchIndex>& prims = primitives.patch;
    if (prims.empty()) return ~0u;
    RTCGeometry geom = rtcNewGeometry(device_->device, type);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), patches.points.size()));
    device_->check("vertex buffer");
    for (std::size_t p = 0; p < patches.points.size(); ++p)
      for (int c = 0; c < 3; ++c) v[3 * p + c] = float(patches.points[p][c]);
    const bool quad = type == RTC_GEOMETRY_TYPE_QUAD;
    const int m = quad ? 4 : 3;
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, quad ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3, m * sizeof(unsigned),
        prims.size()));
    device_->check("index buffer");
    for (std::size_t k = 0; k < prims.size(); ++k) {
      const auto& c = patches.corners[prims[k]];
      // Quads rotated by one corner: Embree splits (q0,q1,q3),(q2,q3,q1), i.e. along p0-p2 after rotation.
      for (int r = 0; r < m; ++r) idx[m * k + r] = unsigned(quad ? c[(r + 1) % 4] : c[r]);
    }
    if (filtered) {
      primitives.normal = &normal_;
      primitives.reject = &reject_;
      rtcSetGeometryUserData(geom, &primitives);
      rtcSetGeometryIntersectFilterFunction(geom, reject_hits);
    }
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(device_->scene, geom);
    rtcReleaseGeometry(geom);
    device_->check("geometry");
    return id;
  };
  for (unsigned kind = 0; kind < 4; ++kind) {
    const unsigned id = add_geometry(kind % 2 ? RTC_GEOMETRY_TYPE_QUAD : RTC_GEOMETRY_TYPE_TRIANGLE,
                                     primitives_[kind], kind >= 2);
    if (id == ~0u) continue;
    if (geometry_kind_.size() <= id) geometry_kind_.resize(id + 1, ~0u);
    geometry_kind_[id] = kind;
  }

  // Step 5: build the BVH.
  rtcCommitScene(device_->scene);
  device_->check("scene build");
}

EmbreeVisibility::~EmbreeVisibility() = default;

Hit EmbreeVisibility::make_hit(unsigned geom_id, unsigned prim_id, float t, const float dir[3]) const {
  Hit h;
  if (geom_id == RTC_INVALID_GEOMETRY_ID) return h;
  h.patch = primitives_[geometry_kind_[geom_id]].patch[prim_id];
  h.t = t;
  const Eigen::Vector3f& nrm = normal_[h.patch];
  h.front = dir[0] * nrm.x() + dir[1] * nrm.y() + dir[2] * nrm.z() < 0.0f;
  return h;
}

Hit EmbreeVisibility::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = rtc_ray(ray, 0);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(device_->scene, &context, &rh);
  const float dir[3] = {rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z};
  return make_hit(rh.hit.geomID, rh.hit.primID, rh.ray.tfar, dir);
}

bool EmbreeVisibility::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = rtc_ray(ray, 0);
  rtcOccluded1(device_->scene, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

void EmbreeVisibility::intersect(const RayPacket& rays, Hit* hits) const {
  const std::size_t m = std::min(rays.count, kPacketSize);
  if (m == 0) return;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit16 rh;
  alignas(64) int valid[16];
  copy_lanes(rh.ray.org_x, rays.org_x, m);
  copy_lanes(rh.ray.org_y, rays.org_y, m);
  copy_lanes(rh.ray.org_z, rays.org_z, m);
  copy_lanes(rh.ray.dir_x, rays.dir_x, m);
  copy_lanes(rh.ray.dir_y, rays.dir_y, m);
  copy_lanes(rh.ray.dir_z, rays.dir_z, m);
  copy_lanes(rh.ray.tfar, rays.tmax, m);
  for (std::size_t k = 0; k < 16; ++k) {
    valid[k] = k < m ? -1 : 0;
    rh.ray.tnear[k] = 0.0f;
    rh.ray.time[k] = 0.0f;
    rh.ray.mask[k] = ~0u;
    rh.ray.id[k] = unsigned(k);
    rh.ray.flags[k] = 0;
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, device_->scene, &context, &rh);
  for (std::size_t k = 0; k < m; ++k) {
    const float dir[3] = {rh.ray.dir_x[k], rh.ray.dir_y[k], rh.ray.dir_z[k]};
    hits[k] = make_hit(rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k], dir);
  }
}

void EmbreeVisibility::intersect(const Ray* rays, Hit* hits, std::size_t n) const {
  RayPacket packet;
  for (std::size_t base = 0; base < n; base += kPacketSize) {
    packet.count = std::min(kPacketSize, n - base);
    for (std::size_t k = 0; k < packet.count; ++k) packet.set(k, rays[base + k]);
    intersect(packet, hits + base);
  }
}

void EmbreeVisibility::occluded(const Ray* rays, bool* out, std::size_t n) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  constexpr std::size_t kStream = 256;
  RTCRay stream[kStream];
  for (std::size_t base = 0; base < n; base += kStream) {
    const std::size_t m = std::min(kStream, n - base);
    for (std::size_t k = 0; k < m; ++k) stream[k] = rtc_ray(rays[base + k], unsigned(k));
    rtcOccluded1M(device_->scene, &context, stream, unsigned(m), sizeof(RTCRay));
    for (std::size_t k = 0; k < m; ++k) out[base + k] = stream[k].tfar < 0.0f;
  }
}

}  // namespace radwalk
