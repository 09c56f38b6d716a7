#include "formfactor/patch_pair_tree.h"

#include <algorithm>
#include <cmath>

#include "core/types.h"
#include "formfactor/point_polygon_form_factor.h"

namespace radwalk {
namespace {

constexpr std::int32_t kLeafSize = 8;
// A far node pair is dropped whole when its boxes' half-diagonals add up to at most this fraction of their distance
// (the one-point estimate errs by about the square of that ratio).
constexpr double kSeparation = 0.25;

// The least distance between two boxes (0 when they overlap or touch).
double box_distance(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, blo[k] - ahi[k], alo[k] - bhi[k]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

// sum_j A_j [-n_j . w]_+ bounded by its axis parts: sum_k [-w_k]_+ P_k+ + [w_k]_+ P_k- (exact for axis normals).
double projected_toward(const std::array<double, 6>& P, const Vec3& w) {
  double s = 0;
  for (int k = 0; k < 3; ++k) s += w[k] < 0 ? -w[k] * P[std::size_t(2 * k)] : w[k] * P[std::size_t(2 * k + 1)];
  return s;
}

}  // namespace

PatchPairTree::PatchPairTree(const PatchSet& patches) : patches_(patches) {
  const std::size_t N = patches.size();
  std::vector<Vec3> lo(N), hi(N);
  for (std::size_t i = 0; i < N; ++i) {
    lo[i] = hi[i] = patches.corner(i, 0);
    for (int k = 1; k < patches.corner_count(i); ++k) {
      lo[i] = lo[i].cwiseMin(patches.corner(i, k));
      hi[i] = hi[i].cwiseMax(patches.corner(i, k));
    }
  }
  order_.resize(N);
  for (std::size_t i = 0; i < N; ++i) order_[i] = std::int32_t(i);
  nodes_.reserve(N / 2 + 2);
  if (N > 0) build(0, std::int32_t(N), lo, hi);
}

std::int32_t PatchPairTree::build(std::int32_t first, std::int32_t count, const std::vector<Vec3>& lo,
                                  const std::vector<Vec3>& hi) {
  const std::int32_t index = std::int32_t(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.first = first;
  node.count = count;
  node.lo = lo[std::size_t(order_[std::size_t(first)])];
  node.hi = hi[std::size_t(order_[std::size_t(first)])];
  Vec3 clo = patches_.centroid[std::size_t(order_[std::size_t(first)])], chi = clo;
  Vec3 sum_n = Vec3::Zero(), sum_c = Vec3::Zero();
  const Vec3 n0 = patches_.normal[std::size_t(order_[std::size_t(first)])];
  bool same = true;
  for (std::int32_t q = first; q < first + count; ++q) {
    const std::size_t i = std::size_t(order_[std::size_t(q)]);
    node.lo = node.lo.cwiseMin(lo[i]);
    node.hi = node.hi.cwiseMax(hi[i]);
    clo = clo.cwiseMin(patches_.centroid[i]);
    chi = chi.cwiseMax(patches_.centroid[i]);
    const double A = patches_.area[i];
    const Vec3& n = patches_.normal[i];
    node.area += A;
    node.max_area = std::max(node.max_area, A);
    sum_n += A * n;
    sum_c += A * patches_.centroid[i];
    same = same && n == n0;
    for (int k = 0; k < 3; ++k) {
      node.projected[std::size_t(2 * k)] += A * std::max(0.0, n[k]);
      node.projected[std::size_t(2 * k + 1)] += A * std::max(0.0, -n[k]);
    }
  }
  node.centroid = node.area > 0 ? Vec3(sum_c / node.area) : Vec3(0.5 * (node.lo + node.hi));
  node.radius = 0.5 * (node.hi - node.lo).norm();
  if (same) {
    node.axis = n0;
    node.spread = 0;
  } else {
    const double len = sum_n.norm();
    node.axis = len > 0 ? Vec3(sum_n / len) : Vec3(0, 0, 1);
    double spread = 0;
    for (std::int32_t q = first; q < first + count; ++q)
      spread = std::max(spread, (patches_.normal[std::size_t(order_[std::size_t(q)])] - node.axis).norm());
    node.spread = spread * (1 + 1e-12) + 1e-12;  // rounding of the norms above
  }
  if (count > kLeafSize) {
    int axis = 0;
    const Vec3 span = chi - clo;
    if (span.y() > span[axis]) axis = 1;
    if (span.z() > span[axis]) axis = 2;
    const std::int32_t half = count / 2;
    std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                     [&](std::int32_t a, std::int32_t b) {
                       const double ca = patches_.centroid[std::size_t(a)][axis], cb = patches_.centroid[std::size_t(b)][axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    node.left = build(first, half, lo, hi);
    node.right = build(first + half, count - half, lo, hi);
  }
  nodes_[std::size_t(index)] = node;
  return index;
}

std::vector<std::int32_t> PatchPairTree::leaf_of_patches() const {
  std::vector<std::int32_t> leaf(patches_.size(), -1);
  for (std::size_t k = 0; k < nodes_.size(); ++k)
    if (nodes_[k].left < 0)
      for (std::int32_t q = nodes_[k].first; q < nodes_[k].first + nodes_[k].count; ++q)
        leaf[std::size_t(order_[std::size_t(q)])] = std::int32_t(k);
  return leaf;
}

PatchPairEnumeration PatchPairTree::enumerate(double threshold) const {
  const std::size_t N = patches_.size();
  PatchPairEnumeration out;
  out.cutoff_bound.assign(N, 0.0);
  out.cutoff_estimate.assign(N, 0.0);
  if (nodes_.empty()) return out;
  // Per node: the bound and the estimate's axis accumulators of its far partners, pushed down to patches at the end.
  std::vector<double> node_bound(nodes_.size(), 0.0);
  std::vector<std::array<double, 6>> node_estimate(nodes_.size(), std::array<double, 6>{});

  // True when every point of box `x` is on or behind the plane of every patch of node y.
  const auto behind = [](const Node& x, const Node& y) {
    double along = 0, length2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double vlo = x.lo[k] - y.hi[k], vhi = x.hi[k] - y.lo[k];
      along += std::max(y.axis[k] * vlo, y.axis[k] * vhi);
      const double m = std::max(std::abs(vlo), std::abs(vhi));
      length2 += m * m;
    }
    return along + y.spread * std::sqrt(length2) <= 0;
  };
  // The one-point estimate's contribution of far partner `b` to the patches of node a (axis accumulators).
  const auto add_far = [&](std::int32_t ia, std::int32_t ib, double d) {
    const Node& a = nodes_[std::size_t(ia)];
    const Node& b = nodes_[std::size_t(ib)];
    node_bound[std::size_t(ia)] += b.area / (kPi * d * d);
    const Vec3 r = b.centroid - a.centroid;
    const double r2 = r.squaredNorm();
    if (!(r2 > 0)) return;
    const Vec3 w = r / std::sqrt(r2);
    const double t = projected_toward(b.projected, w) / (kPi * r2);
    for (int k = 0; k < 3; ++k) {
      node_estimate[std::size_t(ia)][std::size_t(2 * k)] += std::max(0.0, w[k]) * t;
      node_estimate[std::size_t(ia)][std::size_t(2 * k + 1)] += std::max(0.0, -w[k]) * t;
    }
  };

  std::vector<std::array<std::int32_t, 2>> stack;
  stack.push_back({0, 0});
  while (!stack.empty()) {
    const auto [ia, ib] = stack.back();
    stack.pop_back();
    const Node& a = nodes_[std::size_t(ia)];
    const Node& b = nodes_[std::size_t(ib)];
    if (ia == ib) {
      if (a.left < 0) {
        if (a.count > 1) out.leaf_pairs.push_back({ia, ia});
      } else {
        stack.push_back({a.right, a.right});
        stack.push_back({a.left, a.right});
        stack.push_back({a.left, a.left});
      }
      continue;
    }
    if (behind(b, a) || behind(a, b)) {
      ++out.behind_node_pairs;
      continue;
    }
    const bool leaves = a.left < 0 && b.left < 0;
    if (threshold > 0) {
      const double d = box_distance(a.lo, a.hi, b.lo, b.hi);
      if (d > 0 && std::max(a.max_area, b.max_area) / (kPi * d * d) <= threshold) {
        if (a.radius + b.radius <= kSeparation * d) {
          ++out.far_node_pairs;
          out.dropped_pairs += std::uint64_t(a.count) * std::uint64_t(b.count);
          add_far(ia, ib, d);
          add_far(ib, ia, d);
          continue;
        }
        if (leaves) {  // per patch pair: its own box distance and centroids
          out.dropped_pairs += std::uint64_t(a.count) * std::uint64_t(b.count);
          for (std::int32_t p = a.first; p < a.first + a.count; ++p)
            for (std::int32_t q = b.first; q < b.first + b.count; ++q) {
              const std::size_t i = std::size_t(order_[std::size_t(p)]), j = std::size_t(order_[std::size_t(q)]);
              if (!patch_may_see(patches_, i, j)) continue;
              Vec3 ilo = patches_.corner(i, 0), ihi = ilo, jlo = patches_.corner(j, 0), jhi = jlo;
              for (int k = 1; k < patches_.corner_count(i); ++k)
                ilo = ilo.cwiseMin(patches_.corner(i, k)), ihi = ihi.cwiseMax(patches_.corner(i, k));
              for (int k = 1; k < patches_.corner_count(j); ++k)
                jlo = jlo.cwiseMin(patches_.corner(j, k)), jhi = jhi.cwiseMax(patches_.corner(j, k));
              const double dij = box_distance(ilo, ihi, jlo, jhi);
              out.cutoff_bound[i] += patches_.area[j] / (kPi * dij * dij);
              out.cutoff_bound[j] += patches_.area[i] / (kPi * dij * dij);
              const Vec3 r = patches_.centroid[j] - patches_.centroid[i];
              const double r2 = r.squaredNorm();
              const double g = std::max(0.0, patches_.normal[i].dot(r)) * std::max(0.0, -patches_.normal[j].dot(r)) /
                               (kPi * r2 * r2);
              out.cutoff_estimate[i] += patches_.area[j] * g;
              out.cutoff_estimate[j] += patches_.area[i] * g;
            }
          continue;
        }
      }
    }
    if (leaves) {
      out.leaf_pairs.push_back({std::min(ia, ib), std::max(ia, ib)});
      continue;
    }
    const bool split_a = b.left < 0 || (a.left >= 0 && a.radius >= b.radius);
    if (split_a) {
      stack.push_back({a.right, ib});
      stack.push_back({a.left, ib});
    } else {
      stack.push_back({ia, b.right});
      stack.push_back({ia, b.left});
    }
  }
  // Push the nodes' accumulators down to their patches (parents precede children in nodes_).
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Node& node = nodes_[k];
    if (node.left >= 0) {
      for (std::int32_t c : {node.left, node.right}) {
        node_bound[std::size_t(c)] += node_bound[k];
        for (std::size_t s = 0; s < 6; ++s) node_estimate[std::size_t(c)][s] += node_estimate[k][s];
      }
      continue;
    }
    for (std::int32_t q = node.first; q < node.first + node.count; ++q) {
      const std::size_t i = std::size_t(order_[std::size_t(q)]);
      out.cutoff_bound[i] += node_bound[k];
      const Vec3& n = patches_.normal[i];
      double e = 0;
      for (int c = 0; c < 3; ++c)
        e += std::max(0.0, n[c]) * node_estimate[k][std::size_t(2 * c)] +
             std::max(0.0, -n[c]) * node_estimate[k][std::size_t(2 * c + 1)];
      out.cutoff_estimate[i] += e;
    }
  }
  return out;
}

}  // namespace radwalk
