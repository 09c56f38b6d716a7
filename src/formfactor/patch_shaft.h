#pragma once
// Shaft culling of patch pairs (docs/form-factors.md, "The analytic route"): is anything in the scene between
// patches i and j?
//
// The shaft of a pair is the convex hull H of their clipped polygons (polygon_form_factor.h: i's part in front of
// j's plane, j's part in front of i's): every segment from a point of i to a point of j that the form factor
// integrates lies in H. H is described by its face planes, each with its outward normal: the planes of i and j,
// and every plane through an edge of one polygon and a corner of the other that has all corners of both on one
// side (a face of the hull of two convex polygons contains an edge of one of them, or is the plane of one).
// A patch k can block a segment only if it meets H's interior. It cannot when
//   (a) all of k's corners are on or beyond one face plane of H (within `tolerance`), or
//   (b) all corners of both polygons are on one side of k's plane (within `tolerance`),
// two separating-plane tests (a subset of the separating-axis theorem's candidates, so a pair may be called
// "maybe blocked" when nothing blocks: the caller then samples it, never the reverse).
// A patch k covers the shaft (the pair is hidden) when k is convex, k's plane separates the two polygons strictly
// and the crossings of k's plane by the segments between every corner of i and every corner of j lie inside k by
// more than `tolerance`: H n plane(k) is the convex hull of those crossings, so k then meets every segment.
// The patches are found by a bounding-volume hierarchy of their boxes (median splits, at most 4 patches a leaf),
// whose nodes are culled by the same face planes and by H's box. Patches i and j are never tested.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "formfactor/polygon_form_factor.h"
#include "patch/patch_set.h"

namespace radwalk {

enum class ShaftResult { clear, hidden, maybe_blocked };

class PatchShaftTest {
 public:
  // Keeps a reference to the patches (they must outlive this object). tolerance: 1e-9 of the scene's extent.
  explicit PatchShaftTest(const PatchSet& patches);

  // The shaft of patches i and j with their clipped polygons (clip_patch_pair). Thread-safe (const).
  ShaftResult classify(std::size_t i, std::size_t j, const ClippedPair& pair) const;

  double tolerance() const { return tolerance_; }

 private:
  struct Node {
    Vec3 lo, hi;
    std::int32_t left = -1, right = -1;  // children; -1 for a leaf
    std::int32_t first = 0, count = 0;   // a leaf's patches: order_[first .. first + count)
  };
  std::int32_t build(std::int32_t first, std::int32_t count, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                     const std::vector<Vec3>& centre);

  const PatchSet& patches_;
  double tolerance_ = 0;
  std::vector<Node> nodes_;
  std::vector<std::int32_t> order_;
  std::vector<bool> convex_;
};

}  // namespace radwalk
