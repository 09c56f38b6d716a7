#pragma once
// Oriented clusters of input patches above their element trees (Smits, Arvo and Greenberg 1994; Bekaert's
// hierarchical Monte Carlo radiosity with clustering; docs/theory/hierarchical_radiosity.md, "Clusters").
//
// The patches are first grouped by the axis their normal leans to most (+x, -x, +y, -y, +z, -z: every member of a
// group is within 54.7 degrees of its axis), then each group is split recursively into two halves at the median of
// the patch centroids along the longest side of their bounding box, down to clusters of at most `leaf_size`
// patches. Every cluster records its members' total area A_C, N_C = sum_i A_i n_i, its unit mean normal a_C,
// cos_cone_C = min_i n_i . a_C (the half-angle of the cone of its normals), its area-weighted centre and the radius
// of a sphere about that centre holding every member's corners. A group of one patch makes no cluster.
//
// Receiving rule (the oriented cosine rule). A cluster C that receives the incident power P (per channel) of a ray
// from a shooter in direction w (unit, from the shooter towards C) gives member i the irradiance
//     H_i = P (n_i . -w) / (N_C . -w),                                                        (1)
// that is the share w_i = A_i (n_i . -w) / sum_j A_j (n_j . -w) of the power, the share member i would take of
// parallel light from -w if no member shadowed another. The oracle lets C receive only where every n_i . -w > 0
// (cluster_receives below), so every share is >= 0 and sum_i A_i H_i = P exactly: (1) conserves power. (1) is linear
// in P (-w) / (N_C . -w), so a cluster accumulates the irradiance vector
//     G_C += P (-w) / (N_C . -w)          (one 3-vector per channel)
// and member i's irradiance is n_i . G over the clusters that contain it (push: G of a parent is added to its
// children's, N_C is the sum of its children's N, so the power is conserved level by level).
#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

// One irradiance vector per colour channel: row c is channel c's vector G.
using ClusterIrradiance = Eigen::Matrix3d;

struct ClusterTree {
  std::vector<std::int32_t> member;  // patch indices, each cluster's members contiguous: member[begin .. end)
  std::vector<std::int32_t> begin, end;
  std::vector<std::int32_t> parent;          // -1 for a top cluster (one per orientation group)
  std::vector<std::int32_t> child0, child1;  // -1 for a leaf cluster (its members are patches)
  std::vector<Vec3> centre;                  // area-weighted centre of the members' centroids
  std::vector<double> radius;                // every member's corners lie within radius of centre
  std::vector<double> area;                  // A_C
  std::vector<Vec3> normal_sum;              // N_C = sum_i A_i n_i
  std::vector<Vec3> axis;                    // N_C / |N_C|
  std::vector<double> cos_cone;              // min_i n_i . axis
  std::vector<std::int32_t> leaf_of;         // per patch: its leaf cluster, -1 if in none

  std::size_t size() const { return area.size(); }
  bool is_leaf(std::size_t c) const { return child0[c] < 0; }
  // Bytes held by the arrays (capacity), for the run summary.
  std::size_t memory_bytes() const;
};

// The clusters of `patches` (above). leaf_size >= 2. Deterministic: ties in the median split are broken by the
// patch index. Parents have smaller indices than their children (a pass in increasing index is top-down).
ClusterTree make_cluster_tree(const PatchSet& patches, int leaf_size = 8);

// The oracle: true if cluster c may receive, as one element, the rays of a shooter whose centre is `shooter`:
//   d = |centre_C - shooter| > 0,  radius_C / d <= ratio  (the kernel's direction and distance vary over C by about
//   that fraction), and every member faces the shooter's direction: angle(a_C, -w) + cone_C < 90 degrees.
// On true, *toward_shooter = -w (unit).
bool cluster_receives(const ClusterTree& tree, std::size_t c, const Vec3& shooter, double ratio, Vec3* toward_shooter);

// G[c] += P (-w) / (N_C . -w) (per channel), the deposit of incident power P at cluster c from direction -w =
// toward_shooter. Requires cluster_receives(c) to have returned true with this toward_shooter.
void cluster_deposit(const ClusterTree& tree, std::size_t c, const Rgb& P, const Vec3& toward_shooter,
                     std::vector<ClusterIrradiance>& G);

// Pushes G down the clusters (G[child] += G[parent], top-down, in place) and returns per patch the irradiance
// H_i = n_i . G[leaf_of(i)] per channel (0 for a patch in no cluster). sum_i A_i H_i = the power deposited.
std::vector<Rgb> cluster_push(const ClusterTree& tree, const PatchSet& patches, std::vector<ClusterIrradiance>& G);

}  // namespace radwalk
