#include "solve/fluctuation_source.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/discrete_distribution.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "formfactor/point_polygon_form_factor.h"
#include "patch/patch_point_sampler.h"
#include "visibility/ray_offset.h"

namespace radwalk {
namespace {

constexpr int kReplicates = 2;
constexpr int kMaxSide = 8;
constexpr int kMaxNearFieldSide = 16;
constexpr int kPilotStream = 2 * kReplicates;  // streams 0, 1: the replicates; 2, 3: refined for the near field

// Each patch's width: its area over its longest edge.
std::vector<double> widths(const PatchSet& ps) {
  std::vector<double> out(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double longest = 0;
    const int n = ps.corner_count(i);
    for (int k = 0; k < n; ++k) longest = std::max(longest, (ps.corner(i, (k + 1) % n) - ps.corner(i, k)).norm());
    out[i] = longest > 0 ? ps.area[i] / longest : 0.0;
  }
  return out;
}

// The emitters, chosen in proportion to their power A_e sum_c E_ec.
struct Emitters {
  std::vector<std::size_t> patch;
  DiscreteDistribution choice;
};

Emitters find_emitters(const PatchSet& ps) {
  Emitters out;
  std::vector<double> power;
  for (std::size_t e = 0; e < ps.size(); ++e)
    if (ps.E[e].maxCoeff() > 0) {
      out.patch.push_back(e);
      power.push_back(ps.area[e] * ps.E[e].sum());
    }
  if (!power.empty()) out.choice = DiscreteDistribution(power);
  return out;
}

// What one patch shoots: the patches its shot rays hit (front) with their share of d, per replicate.
struct Shot {
  std::int32_t target;
  std::int32_t replicate;
  Rgb value;
};

struct PatchShots {
  std::vector<Shot> shots;
  std::vector<Shot> units;  // per replicate, shot direction and target: the square of the direction's sum
  std::vector<std::int32_t> hits;  // targets of every shot ray that hit a front (the row's F estimate)
  std::vector<Rgb> deltas;  // delta_m of replicate r at r M + m (scaled as B)
  std::vector<std::int32_t> near_targets;  // the thin patches of the near field, ascending (empty: none)
  int side = 0;             // the points per side: the near field's n_j where it has targets, else s_j
  long rays = 0;
};

// The near field of a patch found by its pilot (header): the points per side that resolve it, and its thin targets.
struct NearField {
  int side = 0;
  std::vector<std::int32_t> targets;
};

class Shooter {
 public:
  // B: the solution divided by `scale`; E is divided alike where it is used.
  Shooter(const PatchSet& ps, const Visibility& vis, const PatchRgb& B, double scale, std::uint64_t seed,
          std::vector<int> side, int directions, bool near_field)
      : ps_(ps), vis_(vis), B_(B), scale_(scale), seed_(seed), side_(std::move(side)), L_(directions),
        near_field_(near_field),
        eps_(ray_epsilon(ps)),
        emitters_(find_emitters(ps)),
        width_(widths(ps)) {}

  // Patch j's contributions to d (both replicates). deltas: null, or the deltas and near targets an earlier
  // shoot(j) kept (then the gathers are not traced again: their random numbers are drawn and dropped, so the points,
  // the shot directions and the near targets' points are the same ones).
  void shoot(std::size_t j, PatchShots& out, const std::vector<Rgb>* deltas = nullptr,
             const std::vector<std::int32_t>* near_targets = nullptr) const {
    PointSet points;
    points.side = side_[j];
    NearField near;
    if (deltas) {  // the replay: the side the first shoot(j) used is in its deltas' count
      points.side = int(std::lround(std::sqrt(double(deltas->size() / kReplicates))));
      if (points.side != side_[j] && near_targets) near.targets = *near_targets;
    } else if (near_field_ && side_[j] < kMaxNearFieldSide) {
      near = near_field(j, out);
      if (!near.targets.empty()) points.side = near.side;
    }
    if (!near.targets.empty()) {
      points.stream = kReplicates;
      points.exact = &near.targets;
    }
    out.side = points.side;
    shoot_points(j, points, out, deltas ? deltas->data() : nullptr);
    if (!deltas) out.near_targets = std::move(near.targets);
  }

 private:
  static constexpr double kBelowOne = 0x1.fffffffffffffp-1;
  static constexpr double kEdgeInset = 1e-3;  // of the way from an edge point to the centroid

  // A uniform point of stratum (a, b) of patch j's side x side parametric grid. The second coordinate is drawn
  // first, each in its own statement, so that every compiler draws the same points (as arguments of one call the
  // two draws' order was the compiler's; GCC's, kept here, draws the second first).
  static Vec3 stratified_point(const PatchPointSampler& on_j, int a, int b, int side, Rng& rng) {
    const double v = std::min((b + rng.uniform()) / side, kBelowOne);
    const double u = std::min((a + rng.uniform()) / side, kBelowOne);
    return on_j.point(u, v);
  }

  // A cosine-distributed direction about `frame`'s normal; the draws sequenced as stratified_point's (second first).
  static Vec3 cosine_direction(const Frame& frame, Rng& rng) {
    const double u2 = rng.uniform();
    const double u1 = rng.uniform();
    return frame.to_world(sample_cosine_hemisphere(u1, u2));
  }

  // The pilot of the near field (header): L cosine rays from each of j's own s_j x s_j stratified points (a stream
  // of its own, so that the estimate's points do not decide their own number). Its targets: the patches k (front
  // hit, rho_k > 0) that a pilot ray reaches closer than the points' spacing sqrt(A_j) / s_j and that are thinner
  // than it (k's width w_k = A_k / its longest edge); its side: the points per side that space them no wider than
  // the thinnest target, ceil(sqrt(A_j) / w_min), at most kMaxNearFieldSide (more than s_j, since w_min < the
  // spacing). No target: no near field.
  NearField near_field(std::size_t j, PatchShots& out) const {
    const int side = side_[j], M = side * side;
    const double spacing = std::sqrt(ps_.area[j]) / side;
    const PatchPointSampler on_j(ps_, j);
    const PatchRayOffset offset = patch_ray_offset(ps_, j, eps_);
    const Frame frame(ps_.normal[j]);
    Rng rng = stream(seed_, StreamDomain::discretisation_estimate, j, std::uint64_t(kPilotStream));
    const int corners = ps_.corner_count(j);
    std::vector<Ray> rays(std::size_t(M + corners * side) * L_);
    std::vector<Hit> hits(rays.size());
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) {
        const Vec3 y = stratified_point(on_j, a, b, side, rng);
        for (int l = 0; l < L_; ++l)
          rays[std::size_t(a * side + b) * L_ + l] = spawn_ray(offset, y, cosine_direction(frame, rng));
      }
    // And from `side` stratified points along each edge (a hair inside it): a thin neighbour across an edge is
    // found wherever along the edge it lies, not only where an interior point happens to be near.
    for (int k = 0; k < corners; ++k) {
      const Vec3& p0 = ps_.corner(j, k);
      const Vec3& p1 = ps_.corner(j, (k + 1) % corners);
      for (int q = 0; q < side; ++q) {
        const Vec3 on_edge = p0 + std::min((q + rng.uniform()) / side, kBelowOne) * (p1 - p0);
        const Vec3 y = on_edge + kEdgeInset * (ps_.centroid[j] - on_edge);
        for (int l = 0; l < L_; ++l)
          rays[std::size_t(M + k * side + q) * L_ + l] = spawn_ray(offset, y, cosine_direction(frame, rng));
      }
    }
    vis_.intersect(rays.data(), hits.data(), rays.size());
    out.rays += long(rays.size());
    NearField near;
    double width = std::numeric_limits<double>::infinity();
    for (const Hit& h : hits) {
      if (h.missed() || !h.front || std::size_t(h.patch) == j || !(h.t < spacing)) continue;
      const auto k = static_cast<std::size_t>(h.patch);
      if (!(width_[k] < spacing) || !(ps_.rho[k].maxCoeff() > 0)) continue;
      near.targets.push_back(h.patch);
      width = std::min(width, width_[k]);
    }
    if (near.targets.empty()) return near;
    std::sort(near.targets.begin(), near.targets.end());
    near.targets.erase(std::unique(near.targets.begin(), near.targets.end()), near.targets.end());
    near.side = int(std::min(double(kMaxNearFieldSide), std::ceil(std::sqrt(ps_.area[j]) / std::max(width, 1e-300))));
    return near;
  }

  // The side x side points of replicate r's stream `rng` (into y) and their fluctuation delta_m = rho_j (g_m - mean
  // g) (into delta): g_m gathered along L shared cosine directions and L shared emitter points (header), or, when
  // `given` is set, delta taken from it and the gathers' random numbers drawn and dropped. New deltas are kept in
  // out.deltas.
  void fluctuation_at_points(std::size_t j, int side, Rng& rng, std::vector<Vec3>& y, std::vector<Rgb>& delta,
                             PatchShots& out, const Rgb* given) const {
    const int M = side * side;
    const PatchPointSampler on_j(ps_, j);
    y.resize(std::size_t(M));
    delta.resize(std::size_t(M));
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) y[std::size_t(a * side + b)] = stratified_point(on_j, a, b, side, rng);
    if (given) {
      for (int l = 0; l < L_; ++l) rng.uniform(), rng.uniform();
      if (!emitters_.patch.empty())
        for (int l = 0; l < L_; ++l) rng.uniform(), rng.uniform(), rng.uniform();
      std::copy(given, given + M, delta.begin());
      return;
    }
    const PatchRayOffset offset = patch_ray_offset(ps_, j, eps_);
    const Frame frame(ps_.normal[j]);
    std::vector<Ray> rays(std::size_t(M) * L_);
    std::vector<Hit> hits(rays.size());
    std::vector<Rgb> g(std::size_t(M), Rgb::Zero());
    // The gather g_m: L shared cosine directions (the reflected part) ...
    for (int l = 0; l < L_; ++l) {
      const Vec3 w = cosine_direction(frame, rng);
      for (int m = 0; m < M; ++m) rays[std::size_t(m) * L_ + l] = spawn_ray(offset, y[std::size_t(m)], w);
    }
    vis_.intersect(rays.data(), hits.data(), rays.size());
    out.rays += long(rays.size());
    for (int m = 0; m < M; ++m)
      for (int l = 0; l < L_; ++l) g[std::size_t(m)] += reflected(hits[std::size_t(m) * L_ + l]);
    // ... and L shared emitter points (the emitted part).
    if (!emitters_.patch.empty()) {
      for (int l = 0; l < L_; ++l) {
        const std::size_t k = emitters_.choice.sample(rng.uniform());
        const std::size_t e = emitters_.patch[k];
        const double z2 = rng.uniform();  // sequenced as stratified_point's (second first)
        const double z1 = rng.uniform();
        const Vec3 z = PatchPointSampler(ps_, e).point(z1, z2);
        const Rgb weighted = ps_.E[e] / (scale_ * emitters_.choice.pmf(k));
        for (int m = 0; m < M; ++m) g[std::size_t(m)] += visible_factor(j, offset, y[std::size_t(m)], e, z) * weighted;
        out.rays += M;
      }
    }
    Rgb mean = Rgb::Zero();
    for (Rgb& gm : g) mean += gm /= L_;
    mean /= M;
    for (int m = 0; m < M; ++m) {
      delta[std::size_t(m)] = ps_.rho[j] * (g[std::size_t(m)] - mean);
      out.deltas.push_back(delta[std::size_t(m)]);
    }
  }

  // The points a patch shoots from (header): its own s_j per side from streams 0, 1; where it has near targets, the
  // near field's n_j per side from streams 2, 3, which reach those targets exactly (`exact`) and no shot counts for
  // them.
  struct PointSet {
    int side = 0;
    int stream = 0;
    const std::vector<std::int32_t>* exact = nullptr;  // the near targets, ascending
  };

  // The set's points shoot their fluctuation along L shared directions to the patches they hit on their front
  // (except the near targets; every front hit counts in the row's F estimate), and reach the `exact` targets
  // through the visible point-to-patch factor: replicate r's share of d_k for such a target is sum_m rho_k delta_m
  // A_j F_vis(y_m -> k) / (A_k (M - 1)), F_vis estimated from one uniform point of k (visible_factor: exact where
  // nothing hides it), its variance given the replicate collapsed_strata_variance of the points' terms.
  void shoot_points(std::size_t j, const PointSet& set, PatchShots& out, const Rgb* given) const {
    static const std::vector<std::int32_t> kNone;
    const std::vector<std::int32_t>& skip = set.exact ? *set.exact : kNone;
    const int side = set.side, M = side * side;
    const PatchRayOffset offset = patch_ray_offset(ps_, j, eps_);
    const Frame frame(ps_.normal[j]);
    std::vector<Vec3> y;
    std::vector<Rgb> delta, term(static_cast<std::size_t>(M));
    std::vector<Ray> rays(std::size_t(M) * L_);
    std::vector<Hit> hits(rays.size());
    const double share = ps_.area[j] / (double(M) * L_) * double(M) / (M - 1);
    for (int r = 0; r < kReplicates; ++r) {
      Rng rng = stream(seed_, StreamDomain::discretisation_estimate, j, std::uint64_t(r + set.stream));
      fluctuation_at_points(j, side, rng, y, delta, out, given ? given + std::size_t(r) * M : nullptr);
      for (int l = 0; l < L_; ++l) {
        const Vec3 v = cosine_direction(frame, rng);
        for (int m = 0; m < M; ++m) rays[std::size_t(m) * L_ + l] = spawn_ray(offset, y[std::size_t(m)], v);
      }
      vis_.intersect(rays.data(), hits.data(), rays.size());
      out.rays += long(rays.size());
      std::vector<std::pair<std::int64_t, Rgb>> unit;  // (direction l, target) and the shot's value
      for (int m = 0; m < M; ++m)
        for (int l = 0; l < L_; ++l) {
          const Hit& h = hits[std::size_t(m) * L_ + l];
          if (h.missed() || !h.front) continue;
          const auto k = static_cast<std::size_t>(h.patch);
          out.hits.push_back(h.patch);
          if (!(ps_.rho[k].maxCoeff() > 0) || std::binary_search(skip.begin(), skip.end(), h.patch)) continue;
          out.shots.push_back({h.patch, r, (share / ps_.area[k]) * ps_.rho[k] * delta[std::size_t(m)]});
          unit.push_back({std::int64_t(l) * std::int64_t(ps_.size()) + h.patch, out.shots.back().value});
        }
      // Given the points, the L shot directions are independent, and along one direction the points' shots that
      // reach one target are summed (they cancel where the points see the same place): each (direction, target)
      // sum is one independent term of d's variance.
      std::sort(unit.begin(), unit.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (std::size_t a = 0; a < unit.size();) {
        Rgb sum = Rgb::Zero();
        std::size_t b = a;
        for (; b < unit.size() && unit[b].first == unit[a].first; ++b) sum += unit[b].second;
        out.units.push_back({std::int32_t(unit[a].first % std::int64_t(ps_.size())), r, sum.square()});
        a = b;
      }
      if (!set.exact) continue;
      for (const std::int32_t target : *set.exact) {
        const auto k = static_cast<std::size_t>(target);
        const PatchPointSampler on_k(ps_, k);
        const Rgb weight = ps_.rho[k] * (ps_.area[j] / (ps_.area[k] * (M - 1)));
        Rgb sum = Rgb::Zero();
        for (int m = 0; m < M; ++m) {
          const double z2 = rng.uniform();  // sequenced as stratified_point's (second first)
          const double z1 = rng.uniform();
          const Vec3 z = on_k.point(z1, z2);
          term[std::size_t(m)] = weight * delta[std::size_t(m)] * visible_factor(j, offset, y[std::size_t(m)], k, z);
          sum += term[std::size_t(m)];
        }
        out.rays += M;
        out.shots.push_back({target, r, sum});
        out.units.push_back({target, r, collapsed_strata_variance(term, side)});
      }
    }
  }

  // The variance of the stratified sum of `term` (one value per stratum of a side x side grid, row a * side + b) by
  // collapsed strata: neighbouring strata paired, M / (2 P) sum over the P pairs of their squared difference, which
  // holds both strata's spreads and, where the terms have a trend, its step between them. A near target's terms fall
  // steeply toward it (F_vis), so the strata are paired both ways, along b and along a, and the smaller sum is taken
  // per channel: the pairs that run along the target's edge see the least of that trend.
  static Rgb collapsed_strata_variance(const std::vector<Rgb>& term, int side) {
    Rgb along_b = Rgb::Zero(), along_a = Rgb::Zero();
    int pairs = 0;
    for (int a = 0; a < side; ++a)
      for (int b = 0; b + 1 < side; b += 2, ++pairs) {
        along_b += (term[std::size_t(a * side + b)] - term[std::size_t(a * side + b + 1)]).square();
        along_a += (term[std::size_t(b * side + a)] - term[std::size_t((b + 1) * side + a)]).square();
      }
    return along_b.min(along_a) * (double(side) * side / (2.0 * pairs));
  }

  // (B_h - E) of the patch hit on its front; 0 for an escape or a back hit.
  Rgb reflected(const Hit& h) const {
    if (h.missed() || !h.front) return Rgb::Zero();
    const auto k = static_cast<Eigen::Index>(h.patch);
    return (B_.row(k).transpose() - ps_.E[static_cast<std::size_t>(h.patch)] / scale_).max(0.0);
  }

  // An unbiased estimate of the visible form factor from y (on j) to emitter e, int_e G(y, z) V(y, z) dz, from one
  // uniform point z of e: the exact unoccluded factor (formfactor/point_polygon_form_factor.h) minus the occluded
  // part A_e G(y, z) (1 - V(y, z)). Exact, without noise, where nothing hides z (the usual case, also for an emitter
  // next to y, where G alone would be near-singular).
  double visible_factor(std::size_t j, const PatchRayOffset& offset_j, const Vec3& y, std::size_t e,
                        const Vec3& z) const {
    const double unoccluded = point_patch_form_factor(y, ps_.normal[j], ps_, e);
    if (!(unoccluded > 0)) return 0;
    const Vec3 d = z - y;
    const double r2 = d.squaredNorm();
    if (!(r2 > 0)) return unoccluded;
    const double r = std::sqrt(r2);
    const Vec3 w = d / r;
    const double cos_y = ps_.normal[j].dot(w), cos_z = -ps_.normal[e].dot(w);
    if (!(cos_y > 0 && cos_z > 0)) return unoccluded;
    const Ray shadow = stop_before_plane(spawn_ray(offset_j, y, w), r, z, ps_.normal[e], 4 * eps_);
    if (!(shadow.tmax > 0) || !vis_.occluded(shadow)) return unoccluded;
    return unoccluded - ps_.area[e] * cos_y * cos_z / (kPi * r2);
  }

  const PatchSet& ps_;
  const Visibility& vis_;
  const PatchRgb& B_;
  double scale_;
  std::uint64_t seed_;
  std::vector<int> side_;
  int L_;
  bool near_field_;
  double eps_;
  Emitters emitters_;
  std::vector<double> width_;  // per patch: area / longest edge (a rectangle's shorter side; half a triangle's height)
};

// The points per side s_j of each patch (header): s on a patch of the median area or smaller, round(s sqrt(A_j /
// A_median)) on a larger one, at most kMaxSide.
std::vector<int> point_sides(const PatchSet& patches, int side) {
  const std::size_t N = patches.size();
  std::vector<double> sorted_area(patches.area.begin(), patches.area.end());
  std::nth_element(sorted_area.begin(), sorted_area.begin() + std::ptrdiff_t(N / 2), sorted_area.end());
  const double median_area = N ? sorted_area[N / 2] : 0.0;
  std::vector<int> sides(N, side);
  for (std::size_t j = 0; j < N; ++j)
    if (median_area > 0 && patches.area[j] > median_area)
      sides[j] = std::min(kMaxSide, int(std::lround(side * std::sqrt(patches.area[j] / median_area))));
  return sides;
}

}  // namespace

FluctuationSource fluctuation_source(const PatchSet& patches, const Visibility& visibility, const PatchRgb& B,
                                     int directions, std::uint64_t seed, int points, bool keep_deltas,
                                     bool near_field) {
  const std::size_t N = patches.size();
  const auto n = static_cast<Eigen::Index>(N);
  RADWALK_CHECK_EQ(B.rows(), n);
  RADWALK_CHECK(directions >= 1 && points >= 2);
  const int side = std::max(2, int(std::ceil(std::sqrt(double(points)))));
  const std::vector<int> sides = point_sides(patches, side);
  // Scale before squaring (core/moments.h): B near the largest double has squares beyond it.
  const double scale = moment_scale(N ? B.abs().maxCoeff() : 0.0);
  const PatchRgb scaled = B / scale;
  const Shooter shooter(patches, visibility, scaled, scale, seed, sides, directions, near_field);

  FluctuationSource out;
  if (keep_deltas) {
    out.deltas.resize(N);
    out.near_targets.resize(N);
  }
  out.points = side * side;
  out.directions = directions;
  out.sides.assign(N, 0);
  PatchRgb d[kReplicates] = {PatchRgb::Zero(n, 3), PatchRgb::Zero(n, 3)};
  PatchRgb units = PatchRgb::Zero(n, 3);  // sum over both replicates of the squared (direction, target) sums
  std::vector<Eigen::Triplet<float, std::int32_t>> entries;
  // Chunks of patches shoot in parallel; their contributions are added in patch order (deterministic sums).
  constexpr std::size_t kChunk = 64;
  const std::size_t chunks = (N + kChunk - 1) / kChunk;
  std::size_t next_row = 0;
  // Its rays can outnumber the form factors' (the near field's), so it reports as they do (core/progress.h).
  Progress progress("discretisation error estimate", N);
  ordered_reduce(
      chunks, 2 * std::size_t(std::max(1, active_threads())),
      [&](std::size_t c) {
        std::vector<PatchShots> part(std::min(N, (c + 1) * kChunk) - c * kChunk);
        for (std::size_t j = c * kChunk; j < c * kChunk + part.size(); ++j)
          if (patches.rho[j].maxCoeff() > 0) shooter.shoot(j, part[j - c * kChunk]);
        return part;
      },
      [&](std::vector<PatchShots> part) {
        // Chunks arrive in order: part[q] is patch next_row + q.
        progress.advance(part.size());
        for (std::size_t q = 0; q < part.size(); ++q) {
          for (const Shot& s : part[q].shots) d[s.replicate].row(s.target) += (s.value * scale).transpose();
          for (const Shot& s : part[q].units) units.row(s.target) += (s.value * (scale * scale)).transpose();
          // Row next_row + q of F: run lengths of the sorted hits.
          std::vector<std::int32_t>& h = part[q].hits;
          std::sort(h.begin(), h.end());
          const int side_q = part[q].side;
          out.sides[next_row + q] = side_q;
          if (!part[q].near_targets.empty()) ++out.near_field_patches;
          // The row's shots: 2 M L rays (M = side^2); a replay traces them again and M shadow rays per near target
          // and replicate.
          const long M = long(side_q) * side_q;
          const double per_row = double(kReplicates) * double(M) * directions;
          out.shot_rays += kReplicates * M * (directions + long(part[q].near_targets.size()));
          for (std::size_t a = 0; a < h.size();) {
            std::size_t b = a;
            while (b < h.size() && h[b] == h[a]) ++b;
            entries.emplace_back(std::int32_t(next_row + q), h[a], float(double(b - a) / per_row));
            a = b;
          }
          out.rays += part[q].rays;
          if (keep_deltas) {
            out.deltas[next_row + q] = std::move(part[q].deltas);
            out.near_targets[next_row + q] = std::move(part[q].near_targets);
          }
        }
        next_row += part.size();
      });
  out.d = (d[0] + d[1]) / 2;
  out.replicate[0] = d[0];
  out.replicate[1] = d[1];
  out.variance = (d[0] - d[1]).square() / 4;
  // The replicates' difference has one degree of freedom: by chance it can be near 0 where d rests on a few large
  // shots (a small patch hit from a large one). The (direction, target) units, many per patch, bound it below.
  out.variance = out.variance.max(units / 4);
  out.F = SparseF(n, n);
  out.F.setFromTriplets(entries.begin(), entries.end());
  return out;
}

std::vector<double> weighted_fluctuation_shots(const PatchSet& patches, const Visibility& visibility,
                                               const PatchRgb& B, const FluctuationSource& source,
                                               const PatchRgb (&weights)[2], int directions, std::uint64_t seed,
                                               int points) {
  const std::size_t N = patches.size();
  const auto n = static_cast<Eigen::Index>(N);
  RADWALK_CHECK_EQ(B.rows(), n);
  RADWALK_CHECK_EQ(weights[0].rows(), n);
  RADWALK_CHECK_EQ(weights[1].rows(), n);
  RADWALK_CHECK(directions >= 1 && points >= 2);
  RADWALK_CHECK_EQ(source.deltas.size(), N);
  RADWALK_CHECK_EQ(source.near_targets.size(), N);
  const int side = std::max(2, int(std::ceil(std::sqrt(double(points)))));
  // The same scaling as fluctuation_source, so that the shots are the same numbers; multiplied back per patch.
  const double scale = moment_scale(N ? B.abs().maxCoeff() : 0.0);
  const PatchRgb scaled = B / scale;
  const Shooter shooter(patches, visibility, scaled, scale, seed, point_sides(patches, side), directions, true);
  std::vector<double> out(N, 0.0);
  Progress progress("discretisation error's shooters", N);
  parallel_for(N, [&](std::size_t j) {
    if (patches.rho[j].maxCoeff() > 0) {
      PatchShots shots;
      shooter.shoot(j, shots, &source.deltas[j], &source.near_targets[j]);
      double sum = 0;
      for (const Shot& s : shots.shots) sum += (weights[s.replicate].row(s.target).transpose() * s.value).sum();
      out[j] = sum * scale;
    }
    progress.advance(1);
  }, 16);
  return out;
}

}  // namespace radwalk
