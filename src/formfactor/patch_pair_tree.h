#pragma once
// The candidate pairs of the analytic route by a dual traversal of a bounding-volume hierarchy of the patches
// (docs/theory/polygon_form_factor.md, "Pair enumeration"; docs/form-factors.md, "The analytic route"), instead of
// all N (N - 1) / 2 pairs.
//
// The tree: median splits of the patches' box centres along the longest axis, at most 8 patches a leaf; each node
// keeps its box, its total and largest patch area, its area centroid, a cone holding every normal (axis a, and
// spread s >= |n - a| for every normal n of the node; s = 0 when all normals are equal) and its projected areas
// P_k+ = sum A_j [n_jk]_+, P_k- = sum A_j [-n_jk]_+ along the three axes.
// The traversal takes node pairs (A, B) from (root, root); every unordered patch pair lies in exactly one of the
// node pairs it ends with:
//   - behind: every point of B's box is on or behind the plane of every patch of A (a . v + s |v| <= 0 for every
//     v from A's box to B's box), or the same with A and B swapped: no patch pair of (A, B) faces, nothing kept;
//   - far: the boxes are d > 0 apart, max(largest area of A, largest area of B) / (pi d^2) <= threshold, and the
//     boxes are small against d (their half-diagonals add up to at most d / 4), or both are leaves: every F_ij and
//     F_ji of the pair is at most threshold (F_ij <= A_j / (pi r^2) since both cosines are <= 1, r >= d), and the
//     pairs are dropped: patch i of A gets area(B) / (pi d^2) added to cutoff_bound[i], an upper bound on the
//     sum of its dropped F_ij (occluded or not), and the one-point estimate of its unoccluded sum
//       F_iB ~ [n_i . w]_+ (sum_j A_j [-n_j . w]_+) / (pi r^2),   w = (c_B - c_A) / r, r = |c_B - c_A|,
//     the brackets bounded by their axis parts (exact for axis-aligned normals) to cutoff_estimate[i]; leaf pairs
//     that are not small against d take the same per patch pair (box distance, centroids) instead;
//   - both leaves otherwise: a leaf pair whose patch pairs the caller computes exactly;
//   - else the larger node (by half-diagonal; a leaf never) is split.
// With threshold = 0 nothing is dropped and every facing pair is in a leaf pair. With threshold > 0 every pair
// whose F_ij or F_ji exceeds threshold is kept (its bound does too), and so are pairs of smaller F whose leaves the
// boxes did not separate (within about sqrt(A / (pi threshold)) of each other); the node pairs visited are those
// kept pairs over the leaf sizes plus O(log N) far partners a node, so time and memory grow with N and the kept
// pairs, not with N^2 (measured in docs/form-factors.md).
// Deterministic (one serial traversal); the pairs of the leaf pairs are then computed in parallel by the caller.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "patch/patch_set.h"

namespace radwalk {

struct PatchPairEnumeration {
  // Node pairs whose patch pairs are candidates (a == b: the pairs within one leaf), in traversal order.
  std::vector<std::array<std::int32_t, 2>> leaf_pairs;
  std::vector<double> cutoff_bound;     // per patch i: >= sum of F_ij over its dropped pairs
  std::vector<double> cutoff_estimate;  // per patch i: the one-point estimate of that sum without occlusion
  std::uint64_t dropped_pairs = 0;      // unordered patch pairs dropped (facing or not)
  std::uint64_t far_node_pairs = 0;     // node pairs dropped whole
  std::uint64_t behind_node_pairs = 0;  // node pairs pruned as behind each other
};

class PatchPairTree {
 public:
  // Keeps a reference to the patches (they must outlive the tree).
  explicit PatchPairTree(const PatchSet& patches);

  // threshold >= 0 (finite): see above.
  PatchPairEnumeration enumerate(double threshold) const;

  // The leaf node of every patch (indices of the nodes that leaf_pairs name).
  std::vector<std::int32_t> leaf_of_patches() const;

  // The patches of leaf node k.
  const std::int32_t* leaf_begin(std::int32_t k) const { return order_.data() + nodes_[std::size_t(k)].first; }
  std::int32_t leaf_count(std::int32_t k) const { return nodes_[std::size_t(k)].count; }

 private:
  struct Node {
    Vec3 lo, hi, centroid, axis;
    double area = 0, max_area = 0, spread = 0, radius = 0;
    std::array<double, 6> projected{};  // P_x+, P_x-, P_y+, P_y-, P_z+, P_z-
    std::int32_t left = -1, right = -1, first = 0, count = 0;
  };
  std::int32_t build(std::int32_t first, std::int32_t count, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi);

  const PatchSet& patches_;
  std::vector<Node> nodes_;
  std::vector<std::int32_t> order_;
};

}  // namespace radwalk
