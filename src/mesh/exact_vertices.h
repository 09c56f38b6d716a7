#pragma once
// Vertices of formats that repeat a point at every corner (STL facets, VTK display points split per smoothing
// group) welded to one vertex per exact position, so that faces share their corners as in an OBJ of the same
// surface (edges, orientation and contacts are found between faces that share vertices). Only bit-identical
// coordinates are merged (+0 and -0 are one position; a NaN is never merged): no tolerance moves a point.
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "core/types.h"

namespace radwalk {

class ExactVertices {
 public:
  explicit ExactVertices(std::vector<Vec3>& vertices) : vertices_(vertices) {}
  // The index of the vertex at p, appended to the vertices when p is new.
  std::int32_t index(const Vec3& p) {
    if (!p.allFinite()) return append(p);
    const Key key{bits(p.x()), bits(p.y()), bits(p.z())};
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const std::int32_t i = append(p);
    index_.emplace(key, i);
    return i;
  }

 private:
  struct Key {
    std::uint64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
      h ^= k.y + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      h ^= k.z + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
      return static_cast<std::size_t>(h);
    }
  };
  static std::uint64_t bits(double v) {
    if (v == 0) v = 0;  // -0 and +0 are one position
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  }
  std::int32_t append(const Vec3& p) {
    vertices_.push_back(p);
    return static_cast<std::int32_t>(vertices_.size() - 1);
  }

  std::vector<Vec3>& vertices_;
  std::unordered_map<Key, std::int32_t, Hash> index_;
};

}  // namespace radwalk
