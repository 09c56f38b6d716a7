#include "hierarchy/leaf_patches.h"

#include <cstring>
#include <unordered_map>

#include "core/check.h"

namespace radwalk {
namespace {

struct PointKey {
  std::uint64_t x, y, z;
  bool operator==(const PointKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= k.y + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h ^= k.z + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};
PointKey key_of(const Vec3& p) {
  PointKey k{};
  // +0.0 and -0.0 are the same point.
  const double x = p.x() + 0.0, y = p.y() + 0.0, z = p.z() + 0.0;
  std::memcpy(&k.x, &x, 8);
  std::memcpy(&k.y, &y, 8);
  std::memcpy(&k.z, &z, 8);
  return k;
}

}  // namespace

PatchSet leaf_patches(const PatchSet& roots, const ElementTree& tree, const std::vector<ElementIndex>& leaves) {
  PatchSet p;
  p.source = roots.source;
  p.materials = roots.materials;
  p.input_face_group = roots.input_face_group;
  p.group_object = roots.group_object;
  p.group_name = roots.group_name;
  std::unordered_map<PointKey, std::int32_t, PointKeyHash> index;
  const std::size_t n = leaves.size();
  p.corners.resize(n);
  p.rho.resize(n);
  p.E.resize(n);
  p.face.resize(n);
  p.material.resize(n);
  if (!roots.side.empty()) p.side.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto e = static_cast<std::size_t>(leaves[k]);
    RADWALK_CHECK(tree.is_leaf(e));
    const auto r = static_cast<std::size_t>(tree.root[e]);
    std::array<std::int32_t, 4> c{-1, -1, -1, -1};
    for (int a = 0; a < tree.corner_count[e]; ++a) {
      const Vec3& x = tree.corner[e][static_cast<std::size_t>(a)];
      const auto [it, inserted] = index.try_emplace(key_of(x), static_cast<std::int32_t>(p.points.size()));
      if (inserted) p.points.push_back(x);
      c[static_cast<std::size_t>(a)] = it->second;
    }
    p.corners[k] = c;
    p.rho[k] = roots.rho[r];
    p.E[k] = roots.E[r];
    p.face[k] = roots.face[r];
    p.material[k] = roots.material[r];
    if (!roots.side.empty()) p.side[k] = roots.side[r];
  }
  compute_patch_geometry(p);
  return p;
}

}  // namespace radwalk
