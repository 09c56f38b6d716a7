#include "visibility/visibility.h"

#include "visibility/ray_packet.h"

namespace radwalk {

void Visibility::intersect(const RayPacket& rays, Hit* hits) const {
  for (std::size_t k = 0; k < rays.count; ++k) hits[k] = intersect(rays.ray(k));
}

}  // namespace radwalk
