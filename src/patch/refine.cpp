#include "patch/refine.h"

#include <map>
#include <string>
#include <utility>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

PatchSet split_patches(const PatchSet& patches, const std::vector<bool>& split, std::vector<std::int32_t>* parent) {
  const std::size_t n = patches.size();
  RADWALK_CHECK_EQ(split.size(), n);
  std::size_t splits = 0;
  for (std::size_t i = 0; i < n; ++i) splits += split[i];
  if (n + 3 * splits > kMaxRefinedPatchCount)
    throw InputError("split_patches: " + std::to_string(n + 3 * splits) + " patches would exceed the limit of " +
                     std::to_string(kMaxRefinedPatchCount));

  PatchSet out;
  out.source = patches.source;
  out.materials = patches.materials;
  out.input_face_group = patches.input_face_group;  // names follow the input face, which pieces keep
  out.group_object = patches.group_object;
  out.group_name = patches.group_name;
  out.points = patches.points;
  const std::size_t m = n + 3 * splits;
  out.corners.reserve(m);
  out.rho.reserve(m);
  out.E.reserve(m);
  out.face.reserve(m);
  out.material.reserve(m);
  if (parent) {
    parent->clear();
    parent->reserve(m);
  }

  // Midpoint of the segment between points a and b, created once per unordered pair.
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> midpoints;
  const auto midpoint = [&](std::int32_t a, std::int32_t b) {
    const auto key = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    const auto [it, fresh] = midpoints.try_emplace(key, std::int32_t(out.points.size()));
    if (fresh) out.points.push_back(0.5 * (patches.points[std::size_t(a)] + patches.points[std::size_t(b)]));
    return it->second;
  };
  const auto add = [&](std::size_t from, const std::array<std::int32_t, 4>& c) {
    out.corners.push_back(c);
    out.rho.push_back(patches.rho[from]);
    out.E.push_back(patches.E[from]);
    out.face.push_back(patches.face[from]);
    out.material.push_back(patches.material[from]);
    if (!patches.side.empty()) out.side.push_back(patches.side[from]);  // each side tiles what its parent did
    if (parent) parent->push_back(std::int32_t(from));
  };

  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = patches.corners[i];
    if (!split[i]) {
      add(i, c);
    } else if (patches.is_quad(i)) {
      const std::int32_t m01 = midpoint(c[0], c[1]), m12 = midpoint(c[1], c[2]), m23 = midpoint(c[2], c[3]),
                         m30 = midpoint(c[3], c[0]);
      const std::int32_t centre = std::int32_t(out.points.size());
      out.points.push_back(0.25 * (patches.points[std::size_t(c[0])] + patches.points[std::size_t(c[1])] +
                                   patches.points[std::size_t(c[2])] + patches.points[std::size_t(c[3])]));
      add(i, {c[0], m01, centre, m30});
      add(i, {m01, c[1], m12, centre});
      add(i, {centre, m12, c[2], m23});
      add(i, {m30, centre, m23, c[3]});
    } else {
      const std::int32_t m01 = midpoint(c[0], c[1]), m12 = midpoint(c[1], c[2]), m20 = midpoint(c[2], c[0]);
      add(i, {c[0], m01, m20, -1});
      add(i, {m01, c[1], m12, -1});
      add(i, {m20, m12, c[2], -1});
      add(i, {m01, m12, m20, -1});
    }
  }
  compute_patch_geometry(out);
  return out;
}

}  // namespace radwalk
