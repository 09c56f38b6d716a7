#include "patch/contact_pairs.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <utility>

namespace radwalk {
namespace {

// The corners of patch i as a sorted list of coordinate triples, a triangle's fourth at +inf, so that the same
// points in any order or orientation give the same list (+0 and -0 compare equal, as the readers weld them).
using CornerKey = std::array<std::array<double, 3>, 4>;

CornerKey corner_key(const PatchSet& patches, std::size_t i) {
  constexpr double none = std::numeric_limits<double>::infinity();
  CornerKey key;
  key.fill({none, none, none});
  for (int k = 0; k < patches.corner_count(i); ++k) {
    const Vec3& p = patches.corner(i, k);
    key[static_cast<std::size_t>(k)] = {p.x(), p.y(), p.z()};
  }
  std::sort(key.begin(), key.end());
  return key;
}

// A 64-bit digest of the key (FNV-1a over the coordinates' bits, -0 as +0): equal keys, equal digests.
std::uint64_t digest(const CornerKey& key) {
  std::uint64_t h = 1469598103934665603ull;
  for (const auto& p : key)
    for (double x : p) {
      if (x == 0) x = 0;  // -0 -> +0
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
    }
  return h;
}

}  // namespace

std::vector<std::int32_t> contact_pair_ids(const PatchSet& patches) {
  const std::size_t n = patches.size();
  std::vector<std::int32_t> id(n, -1);
  // Front patches by digest (16 bytes a patch), then each run of equal digests compared by its keys.
  std::vector<std::pair<std::uint64_t, std::size_t>> order;
  order.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!patches.is_back(i)) order.emplace_back(digest(corner_key(patches, i)), i);
  std::sort(order.begin(), order.end());
  std::vector<std::array<std::size_t, 2>> pairs;
  for (std::size_t r = 0; r < order.size();) {
    std::size_t end = r + 1;
    while (end < order.size() && order[end].first == order[r].first) ++end;
    // Within a run (almost always one patch, or the two of a pair), the patches with the same key as each other.
    std::vector<bool> used(end - r, false);
    for (std::size_t a = r; a < end; ++a) {
      if (used[a - r]) continue;
      const CornerKey key = corner_key(patches, order[a].second);
      std::vector<std::size_t> same = {order[a].second};
      for (std::size_t b = a + 1; b < end; ++b)
        if (!used[b - r] && corner_key(patches, order[b].second) == key) {
          used[b - r] = true;
          same.push_back(order[b].second);
        }
      if (same.size() == 2 && patches.normal[same[0]].dot(patches.normal[same[1]]) < 0)
        pairs.push_back({std::min(same[0], same[1]), std::max(same[0], same[1])});
    }
    r = end;
  }
  std::sort(pairs.begin(), pairs.end());
  for (std::size_t k = 0; k < pairs.size(); ++k)
    for (const std::size_t i : pairs[k]) id[i] = static_cast<std::int32_t>(k);
  return id;
}

}  // namespace radwalk
