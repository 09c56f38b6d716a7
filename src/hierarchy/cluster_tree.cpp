#include "hierarchy/cluster_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace radwalk {
namespace {

// The orientation group of a normal: 2 k + (n_k < 0) for the axis k of its largest |component|.
int orientation_group(const Vec3& n) {
  int k = 0;
  n.cwiseAbs().maxCoeff(&k);
  return 2 * k + (n[k] < 0 ? 1 : 0);
}

struct Builder {
  const PatchSet& ps;
  int leaf_size;
  ClusterTree t;

  // A new cluster over member[b .. e) with parent p; its geometry from its members.
  std::int32_t add(std::int32_t b, std::int32_t e, std::int32_t p) {
    const auto c = static_cast<std::int32_t>(t.area.size());
    double A = 0;
    Vec3 N = Vec3::Zero(), x = Vec3::Zero();
    for (std::int32_t k = b; k < e; ++k) {
      const auto i = static_cast<std::size_t>(t.member[static_cast<std::size_t>(k)]);
      A += ps.area[i];
      N += ps.area[i] * ps.normal[i];
      x += ps.area[i] * ps.centroid[i];
    }
    x = A > 0 ? Vec3(x / A) : Vec3(ps.centroid[static_cast<std::size_t>(t.member[static_cast<std::size_t>(b)])]);
    const double nn = N.norm();
    const Vec3 a = nn > 0 ? Vec3(N / nn) : Vec3::UnitZ();
    double cmin = 1, r = 0;
    for (std::int32_t k = b; k < e; ++k) {
      const auto i = static_cast<std::size_t>(t.member[static_cast<std::size_t>(k)]);
      cmin = std::min(cmin, ps.normal[i].dot(a));
      for (int q = 0; q < ps.corner_count(i); ++q) r = std::max(r, (ps.corner(i, q) - x).norm());
    }
    t.begin.push_back(b);
    t.end.push_back(e);
    t.parent.push_back(p);
    t.child0.push_back(-1);
    t.child1.push_back(-1);
    t.centre.push_back(x);
    t.radius.push_back(r);
    t.area.push_back(A);
    t.normal_sum.push_back(N);
    t.axis.push_back(a);
    t.cos_cone.push_back(nn > 0 ? cmin : -1.0);
    return c;
  }

  // Splits cluster c at the median of its members' centroids along the longest side of their bounding box, breadth
  // first so parents precede children.
  void split_all() {
    for (std::size_t c = 0; c < t.area.size(); ++c) {
      const std::int32_t b = t.begin[c], e = t.end[c];
      if (e - b <= leaf_size) continue;
      Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (std::int32_t k = b; k < e; ++k) {
        const Vec3& x = ps.centroid[static_cast<std::size_t>(t.member[static_cast<std::size_t>(k)])];
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
      int axis = 0;
      (hi - lo).maxCoeff(&axis);
      const std::int32_t m = b + (e - b) / 2;
      auto first = t.member.begin() + b, mid = t.member.begin() + m, last = t.member.begin() + e;
      std::nth_element(first, mid, last, [&](std::int32_t i, std::int32_t j) {
        const double xi = ps.centroid[static_cast<std::size_t>(i)][axis], xj = ps.centroid[static_cast<std::size_t>(j)][axis];
        return xi < xj || (xi == xj && i < j);
      });
      const std::int32_t l = add(b, m, static_cast<std::int32_t>(c));
      const std::int32_t r = add(m, e, static_cast<std::int32_t>(c));
      t.child0[c] = l;
      t.child1[c] = r;
    }
  }
};

}  // namespace

std::size_t ClusterTree::memory_bytes() const {
  const std::size_t ints = member.capacity() + begin.capacity() + end.capacity() + parent.capacity() +
                           child0.capacity() + child1.capacity() + leaf_of.capacity();
  return ints * sizeof(std::int32_t) + (centre.capacity() + normal_sum.capacity() + axis.capacity()) * sizeof(Vec3) +
         (radius.capacity() + area.capacity() + cos_cone.capacity()) * sizeof(double);
}

ClusterTree make_cluster_tree(const PatchSet& patches, int leaf_size) {
  RADWALK_CHECK(leaf_size >= 2);
  Builder bld{patches, leaf_size, {}};
  ClusterTree& t = bld.t;
  const std::size_t n = patches.size();
  // Members ordered by orientation group (stable: by index within a group).
  std::array<std::vector<std::int32_t>, 6> groups;
  for (std::size_t i = 0; i < n; ++i)
    groups[static_cast<std::size_t>(orientation_group(patches.normal[i]))].push_back(static_cast<std::int32_t>(i));
  for (const auto& g : groups)
    if (g.size() >= 2) {
      const auto b = static_cast<std::int32_t>(t.member.size());
      t.member.insert(t.member.end(), g.begin(), g.end());
      bld.add(b, static_cast<std::int32_t>(t.member.size()), -1);
    }
  bld.split_all();
  t.leaf_of.assign(n, -1);
  for (std::size_t c = 0; c < t.size(); ++c)
    if (t.is_leaf(c))
      for (std::int32_t k = t.begin[c]; k < t.end[c]; ++k)
        t.leaf_of[static_cast<std::size_t>(t.member[static_cast<std::size_t>(k)])] = static_cast<std::int32_t>(c);
  return t;
}

bool cluster_receives(const ClusterTree& tree, std::size_t c, const Vec3& shooter, double ratio, Vec3* toward_shooter) {
  const Vec3 v = shooter - tree.centre[c];
  const double d = v.norm();
  if (!(d > 0) || tree.radius[c] > ratio * d) return false;
  const Vec3 w = v / d;  // -w of the header: from the cluster towards the shooter
  // angle(a, w) + cone < 90 degrees: both angles below 90 and cos(alpha + theta) > 0 (a small margin for rounding).
  const double ca = tree.axis[c].dot(w), ct = tree.cos_cone[c];
  if (!(ca > 0) || !(ct > 0)) return false;
  const double sa = std::sqrt(std::max(0.0, 1 - ca * ca)), st = std::sqrt(std::max(0.0, 1 - ct * ct));
  if (!(ca * ct - sa * st > 1e-9)) return false;
  *toward_shooter = w;
  return true;
}

void cluster_deposit(const ClusterTree& tree, std::size_t c, const Rgb& P, const Vec3& toward_shooter,
                     std::vector<ClusterIrradiance>& G) {
  const double proj = tree.normal_sum[c].dot(toward_shooter);
  RADWALK_CHECK(proj > 0);
  for (int ch = 0; ch < 3; ++ch) G[c].row(ch) += (P[ch] / proj) * toward_shooter.transpose();
}

std::vector<Rgb> cluster_push(const ClusterTree& tree, const PatchSet& patches, std::vector<ClusterIrradiance>& G) {
  RADWALK_CHECK_EQ(G.size(), tree.size());
  for (std::size_t c = 0; c < tree.size(); ++c)
    if (!tree.is_leaf(c)) {
      G[static_cast<std::size_t>(tree.child0[c])] += G[c];
      G[static_cast<std::size_t>(tree.child1[c])] += G[c];
    }
  std::vector<Rgb> H(patches.size(), Rgb::Zero());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const std::int32_t c = tree.leaf_of[i];
    if (c >= 0) H[i] = (G[static_cast<std::size_t>(c)] * patches.normal[i]).array();
  }
  return H;
}

}  // namespace radwalk
