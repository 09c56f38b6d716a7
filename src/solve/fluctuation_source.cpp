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
constexpr int kNearFieldShotFactor = 4;        // a near-field patch shoots its fluctuation along 4 L directions

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
  int side = 0;             // the points per side used (more than the patch's own where the near field needed)
  int shot_directions = 0;  // the shot directions used (more than L where the near field needed)
  long rays = 0;
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

  // Patch j's contributions to d (both replicates). deltas: null, or the delta_m of an earlier shoot(j) with the
  // same streams (then the gathers are not traced again: their random numbers are drawn and dropped, so the points
  // and the shot directions are the same ones).
  void shoot(std::size_t j, PatchShots& out, const std::vector<Rgb>* deltas = nullptr) const {
    if (deltas) {  // the replay: the side the first shoot(j) used is in its deltas' count
      const int side = int(std::lround(std::sqrt(double(deltas->size() / kReplicates))));
      shoot(j, side, side != side_[j], out, deltas);
    } else {
      const int near = near_field_ && side_[j] < kMaxNearFieldSide ? near_field_side(j, out) : 0;
      shoot(j, near ? near : side_[j], near > 0, out, nullptr);
    }
  }

 private:
  static constexpr double kBelowOne = 0x1.fffffffffffffp-1;

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

  // The pilot of the near-field refinement (header): L cosine rays from each of j's own s_j x s_j stratified points
  // (a stream of its own, so that the estimate's points do not decide their own number). The points per side that
  // space them no wider than the thinnest patch k that a pilot ray reaches closer than their spacing sqrt(A_j) / s_j
  // (k's width w_k = A_k / its longest edge), ceil(sqrt(A_j) / w_k) at most kMaxNearFieldSide, where that is more
  // than s_j; else 0 (no such patch, or none thinner than the spacing: the points resolve what k sees).
  int near_field_side(std::size_t j, PatchShots& out) const {
    const int side = side_[j], M = side * side;
    const double spacing = std::sqrt(ps_.area[j]) / side;
    const PatchPointSampler on_j(ps_, j);
    const PatchRayOffset offset = patch_ray_offset(ps_, j, eps_);
    const Frame frame(ps_.normal[j]);
    Rng rng = stream(seed_, StreamDomain::discretisation_estimate, j, std::uint64_t(kPilotStream));
    std::vector<Ray> rays(std::size_t(M) * L_);
    std::vector<Hit> hits(rays.size());
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b) {
        const Vec3 y = stratified_point(on_j, a, b, side, rng);
        for (int l = 0; l < L_; ++l)
          rays[std::size_t(a * side + b) * L_ + l] =
              spawn_ray(offset, y, cosine_direction(frame, rng));
      }
    vis_.intersect(rays.data(), hits.data(), rays.size());
    out.rays += long(rays.size());
    double width = std::numeric_limits<double>::infinity();
    for (const Hit& h : hits)
      if (!h.missed() && std::size_t(h.patch) != j && h.t < spacing) width = std::min(width, width_[h.patch]);
    if (!(width < std::numeric_limits<double>::infinity())) return 0;
    const double wanted = std::min(double(kMaxNearFieldSide), std::ceil(std::sqrt(ps_.area[j]) / std::max(width, 1e-300)));
    return wanted > side ? int(wanted) : 0;
  }

  // shoot(j) with side x side points a replicate; `near_field`: the points of the near-field refinement (header),
  // drawn from streams of their own, and their fluctuation shot along 4 L directions.
  void shoot(std::size_t j, int side, bool near_field, PatchShots& out, const std::vector<Rgb>* deltas) const {
    const int M = side * side;
    const int Ls = near_field ? kNearFieldShotFactor * L_ : L_;
    out.side = side;
    out.shot_directions = Ls;
    const PatchPointSampler on_j(ps_, j);
    const PatchRayOffset offset = patch_ray_offset(ps_, j, eps_);
    const Frame frame(ps_.normal[j]);
    std::vector<Vec3> y(M);
    std::vector<Ray> rays(std::size_t(M) * Ls);
    std::vector<Hit> hits(rays.size());
    std::vector<Rgb> g(M);
    for (int r = 0; r < kReplicates; ++r) {
      Rng rng = stream(seed_, StreamDomain::discretisation_estimate, j,
                       std::uint64_t(r + (near_field ? kReplicates : 0)));
      for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b)
          y[a * side + b] = stratified_point(on_j, a, b, side, rng);
      Rgb mean = Rgb::Zero();
      if (deltas) {
        for (int l = 0; l < L_; ++l) rng.uniform(), rng.uniform();
        if (!emitters_.patch.empty())
          for (int l = 0; l < L_; ++l) rng.uniform(), rng.uniform(), rng.uniform();
      } else {
        // The gather g_m: L shared cosine directions (the reflected part) ...
        for (int l = 0; l < L_; ++l) {
          const Vec3 w = cosine_direction(frame, rng);
          for (int m = 0; m < M; ++m) rays[std::size_t(m) * L_ + l] = spawn_ray(offset, y[m], w);
        }
        vis_.intersect(rays.data(), hits.data(), std::size_t(M) * L_);
        out.rays += long(M) * L_;
        for (int m = 0; m < M; ++m) {
          g[m] = Rgb::Zero();
          for (int l = 0; l < L_; ++l) g[m] += reflected(hits[std::size_t(m) * L_ + l]);
        }
        // ... and L shared emitter points (the emitted part).
        if (!emitters_.patch.empty()) {
          for (int l = 0; l < L_; ++l) {
            const std::size_t k = emitters_.choice.sample(rng.uniform());
            const std::size_t e = emitters_.patch[k];
            const double z2 = rng.uniform();  // sequenced as stratified_point's (second first)
            const double z1 = rng.uniform();
            const Vec3 z = PatchPointSampler(ps_, e).point(z1, z2);
            const Rgb weighted = ps_.E[e] / (scale_ * emitters_.choice.pmf(k));
            for (int m = 0; m < M; ++m) g[m] += visible_factor(j, offset, y[m], e, z) * weighted;
            out.rays += M;
          }
        }
        for (int m = 0; m < M; ++m) mean += g[m] /= L_;
        mean /= M;
      }
      // The fluctuation delta_m, shot along Ls shared directions (L, or L' = 4 L in the near field).
      for (int l = 0; l < Ls; ++l) {
        const Vec3 v = cosine_direction(frame, rng);
        for (int m = 0; m < M; ++m) rays[std::size_t(m) * Ls + l] = spawn_ray(offset, y[m], v);
      }
      vis_.intersect(rays.data(), hits.data(), rays.size());
      out.rays += long(rays.size());
      const double share = ps_.area[j] / (double(M) * Ls) * double(M) / (M - 1);
      std::vector<std::pair<std::int64_t, Rgb>> unit;  // (direction l, target) and the shot's value
      for (int m = 0; m < M; ++m) {
        const Rgb delta = deltas ? (*deltas)[std::size_t(r) * M + m] : Rgb(ps_.rho[j] * (g[m] - mean));
        if (!deltas) out.deltas.push_back(delta);
        for (int l = 0; l < Ls; ++l) {
          const Hit& h = hits[std::size_t(m) * Ls + l];
          if (h.missed() || !h.front) continue;
          const auto k = static_cast<std::size_t>(h.patch);
          out.hits.push_back(h.patch);
          if (!(ps_.rho[k].maxCoeff() > 0)) continue;
          out.shots.push_back({h.patch, r, (share / ps_.area[k]) * ps_.rho[k] * delta});
          unit.push_back({std::int64_t(l) * std::int64_t(ps_.size()) + h.patch, out.shots.back().value});
        }
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
    }
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
  if (keep_deltas) out.deltas.resize(N);
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
          if (side_q > 0 && side_q != sides[next_row + q]) ++out.near_field_patches;
          const double per_row = double(kReplicates) * side_q * side_q * part[q].shot_directions;
          for (std::size_t a = 0; a < h.size();) {
            std::size_t b = a;
            while (b < h.size() && h[b] == h[a]) ++b;
            entries.emplace_back(std::int32_t(next_row + q), h[a], float(double(b - a) / per_row));
            a = b;
          }
          out.rays += part[q].rays;
          if (keep_deltas) out.deltas[next_row + q] = std::move(part[q].deltas);
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
      shooter.shoot(j, shots, &source.deltas[j]);
      double sum = 0;
      for (const Shot& s : shots.shots) sum += (weights[s.replicate].row(s.target).transpose() * s.value).sum();
      out[j] = sum * scale;
    }
    progress.advance(1);
  }, 16);
  return out;
}

}  // namespace radwalk
