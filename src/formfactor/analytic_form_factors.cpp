#include "formfactor/analytic_form_factors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/sobol.h"
#include "formfactor/patch_pair_tree.h"
#include "formfactor/patch_shaft.h"
#include "formfactor/point_polygon_form_factor.h"
#include "formfactor/polygon_form_factor.h"
#include "visibility/ray_offset.h"

namespace radwalk {
namespace {

void check_options(const AnalyticFormFactorOptions& o) {
  const auto bad = [](const std::string& what) { return InputError(locate("analytic form factor options", 0, -1, what)); };
  const auto power_of_two = [](long m) { return m >= 1 && (m & (m - 1)) == 0; };
  if (!power_of_two(o.min_visibility_samples) || o.min_visibility_samples < 2 || o.min_visibility_samples > (1L << 24))
    throw bad("min_visibility_samples must be a power of 2 in [2, 2^24], got " + std::to_string(o.min_visibility_samples));
  if (!power_of_two(o.max_visibility_samples) || o.max_visibility_samples > (1L << 24) ||
      o.max_visibility_samples < o.min_visibility_samples)
    throw bad("max_visibility_samples must be a power of 2 in [min_visibility_samples, 2^24], got " +
              std::to_string(o.max_visibility_samples));
  if (!(o.cutoff >= 0) || !(o.cutoff < 1))
    throw bad("cutoff must be in [0, 1), got " + std::to_string(o.cutoff));
  if (o.cutoff_rays < 0 || o.cutoff_rays > (1L << 24) || (o.cutoff_rays > 0 && !(o.cutoff > 0)))
    throw bad("cutoff_rays must be in [0, 2^24] and needs cutoff > 0, got " + std::to_string(o.cutoff_rays));
  if (!(o.visibility_tolerance > 0) || !std::isfinite(o.visibility_tolerance))
    throw bad("visibility_tolerance must be finite and > 0, got " + std::to_string(o.visibility_tolerance));
}

// Uniform points on a convex polygon: a fan of triangles from corner 0, one chosen in proportion to its area.
class PolygonSampler {
 public:
  PolygonSampler(const Vec3* p, int count) : p_(p), count_(count) {
    double total = 0;
    for (int k = 1; k + 1 < count; ++k) {
      total += 0.5 * (p[k] - p[0]).cross(p[k + 1] - p[0]).norm();
      cdf_[k - 1] = total;
    }
    for (int k = 0; k + 2 < count; ++k) cdf_[k] /= total;
    cdf_[count - 3] = 1.0;
  }
  Vec3 point(double u1, double u2) const {
    int t = 0;
    while (t < count_ - 3 && u1 >= cdf_[t]) ++t;
    const double lo = t > 0 ? cdf_[t - 1] : 0.0, width = cdf_[t] - lo;
    u1 = width > 0 ? std::min((u1 - lo) / width, 1.0) : 0.5;
    const double s = std::sqrt(u1);
    return (1 - s) * p_[0] + s * (1 - u2) * p_[t + 1] + s * u2 * p_[t + 2];
  }

 private:
  const Vec3* p_;
  int count_;
  double cdf_[kMaxPolygonCorners] = {};
};

struct PairEntry {
  std::int32_t j;
  double G;   // exchange area x visibility
  double se;  // standard error of the visibility fraction
  bool estimated;
};

struct Counts {
  std::uint64_t clear = 0, hidden = 0, sampled = 0, rays = 0;
};

struct VisibilityEstimate {
  double V = 1, se = 0;
};

// The visibility fraction of a pair (analytic_form_factors.h, "Visibility"): a pilot of 16 point pairs chooses the
// form and the sample count, then M fresh point pairs (an independent shift) give the estimate.
VisibilityEstimate estimate_visibility(const PatchSet& ps, const Visibility& vis, const AnalyticFormFactorOptions& o,
                                       double eps, std::size_t i, std::size_t j, const ClippedPair& pair, double G,
                                       std::uint64_t& rays) {
  Rng rng = stream(o.seed, StreamDomain::analytic_visibility, i, j);
  const PolygonSampler on_i(pair.p, pair.np), on_j(pair.q, pair.nq);
  double area_i = 0, area_j = 0;
  for (int k = 1; k + 1 < pair.np; ++k) area_i += 0.5 * (pair.p[k] - pair.p[0]).cross(pair.p[k + 1] - pair.p[0]).norm();
  for (int k = 1; k + 1 < pair.nq; ++k) area_j += 0.5 * (pair.q[k] - pair.q[0]).cross(pair.q[k + 1] - pair.q[0]).norm();
  // E[g] for uniform x on i's clipped polygon and y on j's: g = cos_x cos_y / (pi r^2), G = A_i A_j E[g].
  const double mean_g = G / (area_i * area_j);
  const PatchRayOffset offset = patch_ray_offset(ps, i, eps);
  const Vec3& ni = ps.normal[i];
  const Vec3& nj = ps.normal[j];
  constexpr std::size_t kBatch = 64;
  Ray batch[kBatch];
  double weight[kBatch];
  bool blocked[kBatch];
  // Traces samples [0, M) with `shift`; calls score(g_s / E[g], v_s) per sample (g = 0 samples score (0, 1)).
  const auto run = [&](long M, const SobolShift& shift, auto&& score) {
    std::size_t pending = 0;
    const auto trace = [&] {
      vis.occluded(batch, blocked, pending);
      for (std::size_t q = 0; q < pending; ++q) score(weight[q], !blocked[q]);
      rays += pending;
      pending = 0;
    };
    for (long s = 0; s < M; ++s) {
      const auto u = sobol_point(std::uint32_t(s), shift);
      const Vec3 x = on_i.point(u[0], u[1]), y = on_j.point(u[2], u[3]);
      const Vec3 d = y - x;
      const double r2 = d.squaredNorm();
      const double r = std::sqrt(r2);
      const Vec3 w = d / r;
      const double cos_x = ni.dot(w), cos_y = -nj.dot(w);
      if (!(r2 > 0) || !(cos_x > 0) || !(cos_y > 0)) {
        score(0.0, true);
        continue;
      }
      const Ray ray = stop_before_plane(spawn_ray(offset, x, w), r, pair.q[0], nj, 4 * eps);
      if (!(ray.tmax > 0)) {
        score(cos_x * cos_y / (kPi * r2) / mean_g, true);
        continue;
      }
      batch[pending] = ray;
      weight[pending] = cos_x * cos_y / (kPi * r2) / mean_g;
      if (++pending == kBatch) trace();
    }
    if (pending) trace();
  };
  SobolShift pilot_shift, shift;
  for (auto& w : pilot_shift.word) w = rng.next_u32();
  for (auto& w : shift.word) w = rng.next_u32();
  // Pilot: the visible share of the weight decides the form; the chosen form's terms give the variance per sample.
  constexpr long kPilot = 16;
  double pw[kPilot], pv[kPilot];
  long np = 0;
  run(kPilot, pilot_shift, [&](double w, bool v) { pw[np] = w, pv[np] = v ? 1.0 : 0.0, ++np; });
  double W = 0, WV = 0;
  for (long k = 0; k < np; ++k) W += pw[k], WV += pw[k] * pv[k];
  const bool mostly_visible = !(W > 0) || WV >= 0.5 * W;
  // Terms: visible form t = w v (exactly 0 when every segment is blocked); blocked form t = 1 - w (1 - v)
  // (exactly 1 when none is). Both have mean V.
  const auto term = [mostly_visible](double w, double v) { return mostly_visible ? 1 - w * (1 - v) : w * v; };
  double m1 = 0, m2 = 0;
  for (long k = 0; k < np; ++k) m1 += term(pw[k], pv[k]);
  m1 /= double(np);
  for (long k = 0; k < np; ++k) m2 += (term(pw[k], pv[k]) - m1) * (term(pw[k], pv[k]) - m1);
  const double pilot_var = m2 / double(np - 1);
  long M = o.min_visibility_samples;
  while (M < o.max_visibility_samples && pilot_var / double(M) > o.visibility_tolerance * o.visibility_tolerance) M *= 2;
  // The estimate from M fresh samples.
  double sum = 0, sum2 = 0;
  long n = 0;
  run(M, shift, [&](double w, bool v) {
    const double t = term(w, v ? 1.0 : 0.0);
    sum += t;
    sum2 += t * t;
    ++n;
  });
  VisibilityEstimate est;
  const double mean = sum / double(n);
  const double var = std::max(0.0, (sum2 - double(n) * mean * mean) / double(n - 1));
  est.V = std::max(0.0, mean);
  // The sample variance is 0 when every sample agreed; 1 / M then stands for the fraction M samples could miss.
  est.se = std::max(std::sqrt(var / double(n)), 1.0 / double(n));
  return est;
}

// The dropped pairs' entries by cosine rays (analytic_form_factors.h, "Completion"): row i's n rays (Sobol points,
// the shift from stream(seed, analytic_visibility, i, i)) count their front hits c_ij on patches j of dropped pairs;
// each pair gets G_ij = (A_i c_ij / n + A_j c_ji / n) / 2 with the binomial variance of the two halves, added to
// rows (as estimated entries; rows are re-sorted by the caller).
void complete_dropped_pairs(const PatchSet& ps, const Visibility& vis, const PatchPairTree& tree,
                            const PatchPairEnumeration& pairs, const AnalyticFormFactorOptions& o, double eps,
                            std::vector<std::vector<PairEntry>>& rows, AnalyticFormFactors& out) {
  const std::size_t N = ps.size();
  const std::vector<std::int32_t> leaf = tree.leaf_of_patches();
  std::vector<std::uint64_t> kept;
  kept.reserve(pairs.leaf_pairs.size());
  const auto key = [](std::int32_t a, std::int32_t b) {
    if (a > b) std::swap(a, b);
    return std::uint64_t(std::uint32_t(a)) << 32 | std::uint32_t(b);
  };
  for (const auto& lp : pairs.leaf_pairs) kept.push_back(key(lp[0], lp[1]));
  std::sort(kept.begin(), kept.end());
  const long n = o.cutoff_rays;
  // Per row: (j, count) of its rays' hits on dropped pairs.
  std::vector<std::vector<std::pair<std::int32_t, std::uint32_t>>> hits(N);
  std::vector<std::uint64_t> rays(N, 0);
  parallel_chunks(N, 16, [&](std::size_t b, std::size_t e) {
    constexpr std::size_t kBatch = 64;
    Ray batch[kBatch];
    Hit hit[kBatch];
    std::vector<std::int32_t> targets;
    for (std::size_t i = b; i < e; ++i) {
      Rng rng = stream(o.seed, StreamDomain::analytic_visibility, i, i);
      SobolShift shift;
      for (auto& w : shift.word) w = rng.next_u32();
      Vec3 corners[4];
      const int count = ps.corner_count(i);
      for (int k = 0; k < count; ++k) corners[k] = ps.corner(i, k);
      const PolygonSampler on_i(corners, count);
      const Frame frame(ps.normal[i]);
      const PatchRayOffset offset = patch_ray_offset(ps, i, eps);
      targets.clear();
      for (long base = 0; base < n; base += long(kBatch)) {
        const std::size_t m = std::size_t(std::min<long>(long(kBatch), n - base));
        for (std::size_t k = 0; k < m; ++k) {
          const auto u = sobol_point(std::uint32_t(base + long(k)), shift);
          batch[k] = spawn_ray(offset, on_i.point(u[0], u[1]), frame.to_world(sample_cosine_hemisphere(u[2], u[3])));
        }
        vis.intersect(batch, hit, m);
        for (std::size_t k = 0; k < m; ++k) {
          const Hit& h = hit[k];
          if (h.missed() || !h.front || std::size_t(h.patch) == i) continue;
          if (std::binary_search(kept.begin(), kept.end(), key(leaf[i], leaf[std::size_t(h.patch)]))) continue;
          targets.push_back(std::int32_t(h.patch));
        }
      }
      rays[i] = std::uint64_t(n);
      std::sort(targets.begin(), targets.end());
      for (std::size_t k = 0; k < targets.size();) {
        std::size_t l = k;
        while (l < targets.size() && targets[l] == targets[k]) ++l;
        hits[i].push_back({targets[k], std::uint32_t(l - k)});
        k = l;
      }
    }
  });
  // Both halves of each pair: (min, max) -> G and variance, in order.
  struct Half {
    std::int32_t lo, hi;
    double g, var;
  };
  std::vector<Half> halves;
  for (std::size_t i = 0; i < N; ++i) {
    out.cutoff_rays += rays[i];
    for (const auto& [j, c] : hits[i]) {
      const double p = double(c) / double(n);
      const double A = ps.area[i];
      halves.push_back({std::int32_t(std::min<std::size_t>(i, std::size_t(j))),
                        std::int32_t(std::max<std::size_t>(i, std::size_t(j))), 0.5 * A * p,
                        0.25 * A * A * p * (1 - p) / double(n)});
    }
  }
  std::sort(halves.begin(), halves.end(),
            [](const Half& x, const Half& y) { return x.lo < y.lo || (x.lo == y.lo && x.hi < y.hi); });
  for (std::size_t k = 0; k < halves.size();) {
    std::size_t l = k;
    double g = 0, var = 0;
    while (l < halves.size() && halves[l].lo == halves[k].lo && halves[l].hi == halves[k].hi) g += halves[l].g, var += halves[l].var, ++l;
    rows[std::size_t(halves[k].lo)].push_back({halves[k].hi, g, std::sqrt(var), true});
    ++out.completed_pairs;
    k = l;
  }
}

// Brings rows whose sum exceeds 1 + 1e-12 down to 1 (analytic_form_factors.h, "Rows above 1").
void scale_rows_above_one(const PatchSet& ps, std::vector<std::vector<PairEntry>>& rows, AnalyticFormFactors& out) {
  const std::size_t N = ps.size();
  std::vector<double> sum(N, 0.0);
  for (std::size_t i = 0; i < N; ++i)
    for (const PairEntry& e : rows[i]) {
      sum[i] += e.G / ps.area[i];
      sum[std::size_t(e.j)] += e.G / ps.area[std::size_t(e.j)];
    }
  bool any = false;
  for (std::size_t i = 0; i < N; ++i) {
    out.largest_row_excess = std::max(out.largest_row_excess, sum[i] - 1);
    any = any || sum[i] > 1 + 1e-12;
  }
  if (!any) return;
  // Every entry of a row: (owner row, index in its list).
  std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> touching(N);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < rows[i].size(); ++k) {
      touching[i].push_back({std::int32_t(i), std::int32_t(k)});
      touching[std::size_t(rows[i][k].j)].push_back({std::int32_t(i), std::int32_t(k)});
    }
  const auto change = [&](PairEntry& e, std::size_t owner, double factor) {
    const double dG = e.G * (1 - factor);
    e.G *= factor;
    e.se *= factor;
    sum[owner] -= dG / ps.area[owner];
    sum[std::size_t(e.j)] -= dG / ps.area[std::size_t(e.j)];
  };
  for (std::size_t i = 0; i < N; ++i) {
    if (!(sum[i] > 1 + 1e-12)) continue;
    ++out.rows_scaled;
    double estimated = 0;
    for (const auto& t : touching[i]) {
      const PairEntry& e = rows[std::size_t(t.first)][std::size_t(t.second)];
      if (e.estimated) estimated += e.G / ps.area[i];
    }
    const double excess = sum[i] - 1;
    const bool only_estimated = estimated > excess;
    const double factor = only_estimated ? (estimated - excess) / estimated : 1 / sum[i];
    for (const auto& t : touching[i]) {
      PairEntry& e = rows[std::size_t(t.first)][std::size_t(t.second)];
      if (!only_estimated || e.estimated) change(e, std::size_t(t.first), factor);
    }
  }
}

}  // namespace

AnalyticFormFactors analytic_form_factors(const PatchSet& ps, const Visibility& vis,
                                          const AnalyticFormFactorOptions& options) {
  check_options(options);
  const std::size_t N = ps.size();
  if (options.cutoff == 0 && N > options.max_patches)
    throw InputError(locate(ps.source, 0, -1,
                            "--analytic without a cut-off computes every facing pair of patches (time N^2) and is "
                            "limited to " + std::to_string(options.max_patches) + " patches; this scene has " +
                            std::to_string(N) + " (give --analytic-cutoff, use the ray route, or a coarser --max-edge)"));
  AnalyticFormFactors out;
  out.cutoff = options.cutoff;
  const double eps = ray_epsilon(ps);
  const PatchShaftTest shaft(ps);
  std::vector<std::vector<PairEntry>> rows(N);
  const PatchPairTree tree(ps);
  PatchPairEnumeration pairs = tree.enumerate(options.cutoff);
  out.cutoff_bound = std::move(pairs.cutoff_bound);
  out.cutoff_estimate = std::move(pairs.cutoff_estimate);
  out.dropped_pairs = pairs.dropped_pairs;
  {
    // Each leaf pair's patch pairs (i < j), computed in parallel, each task into its own list.
    const std::size_t T = pairs.leaf_pairs.size();
    std::vector<std::vector<std::pair<std::int32_t, PairEntry>>> found(T);
    std::vector<Counts> counts(T);
    Progress progress("form factors (analytic)", T);
    parallel_chunks(T, 16, [&](std::size_t b, std::size_t e) {
      for (std::size_t t = b; t < e; ++t) {
        Counts& c = counts[t];
        const auto pair_of = [&](std::size_t i, std::size_t j) {
          if (i > j) std::swap(i, j);
          if (!patch_may_see(ps, i, j)) return;
          ClippedPair pair;
          if (!clip_patch_pair(ps, i, j, pair)) return;
          const double G = patch_exchange_area(ps, i, j);
          if (!(G > 0)) return;
          const ShaftResult r = shaft.classify(i, j, pair);
          if (r == ShaftResult::clear) {
            ++c.clear;
            found[t].push_back({std::int32_t(i), {std::int32_t(j), G, 0.0, false}});
          } else if (r == ShaftResult::hidden) {
            ++c.hidden;
          } else {
            ++c.sampled;
            const VisibilityEstimate v = estimate_visibility(ps, vis, options, eps, i, j, pair, G, c.rays);
            if (v.V > 0 || v.se > 0) found[t].push_back({std::int32_t(i), {std::int32_t(j), G * v.V, v.se * G, true}});
          }
        };
        const auto [la, lb] = pairs.leaf_pairs[t];
        const std::int32_t* A = tree.leaf_begin(la);
        const std::int32_t* B = tree.leaf_begin(lb);
        const std::int32_t na = tree.leaf_count(la), nb = tree.leaf_count(lb);
        for (std::int32_t p = 0; p < na; ++p)
          for (std::int32_t q = la == lb ? p + 1 : 0; q < nb; ++q) pair_of(std::size_t(A[p]), std::size_t(B[q]));
      }
      progress.advance(e - b);
    });
    progress.finish();
    for (const Counts& c : counts) {
      out.clear_pairs += c.clear;
      out.hidden_pairs += c.hidden;
      out.sampled_pairs += c.sampled;
      out.visibility_rays += c.rays;
    }
    // Into rows (pair i < j in row i), each row in order of j: the CSR assembly below needs them so.
    std::vector<std::size_t> per_row(N, 0);
    for (const auto& list : found)
      for (const auto& f : list) ++per_row[std::size_t(f.first)];
    for (std::size_t i = 0; i < N; ++i) rows[i].reserve(per_row[i]);
    for (auto& list : found) {
      for (const auto& f : list) rows[std::size_t(f.first)].push_back(f.second);
      std::vector<std::pair<std::int32_t, PairEntry>>().swap(list);
    }
  }
  if (options.cutoff_rays > 0 && out.dropped_pairs > 0)
    complete_dropped_pairs(ps, vis, tree, pairs, options, eps, rows, out);
  parallel_chunks(N, 256, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      std::sort(rows[i].begin(), rows[i].end(), [](const PairEntry& x, const PairEntry& y) { return x.j < y.j; });
  });
  out.pairs = out.clear_pairs + out.hidden_pairs + out.sampled_pairs;
  scale_rows_above_one(ps, rows, out);

  // CSR, columns increasing: row r gets columns i < r from the pairs (i, r), taken in order of i, then its own
  // pairs (r, j > r) in order of j.
  std::vector<std::size_t> nnz(N, 0);
  for (std::size_t i = 0; i < N; ++i)
    for (const PairEntry& e : rows[i])
      if (e.G > 0) ++nnz[i], ++nnz[std::size_t(e.j)];
  std::size_t total = 0;
  for (std::size_t i = 0; i < N; ++i) total += nnz[i];
  if (total > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw InputError(locate(ps.source, 0, -1, "form-factor matrix has more than 2^31-1 non-zeros"));
  FormFactors& ff = out.form_factors;
  ff.F.resize(Eigen::Index(N), Eigen::Index(N));
  ff.F.resizeNonZeros(Eigen::Index(total));
  std::int32_t* outer = ff.F.outerIndexPtr();
  std::int32_t* cols = ff.F.innerIndexPtr();
  float* values = ff.F.valuePtr();
  outer[0] = 0;
  for (std::size_t i = 0; i < N; ++i) outer[i + 1] = outer[i] + std::int32_t(nnz[i]);
  std::vector<std::int32_t> at(outer, outer + N);
  out.entry_std_error.assign(total, 0.0f);
  std::vector<double> variance(N, 0.0);
  for (std::size_t i = 0; i < N; ++i)
    for (const PairEntry& e : rows[i]) {
      const std::size_t j = std::size_t(e.j);
      if (e.G > 0) {  // a sampled pair estimated at 0 keeps only its variance
        out.entry_std_error[std::size_t(at[j])] = float(e.se / ps.area[j]);
        cols[at[j]] = std::int32_t(i);
        values[at[j]++] = float(e.G / ps.area[j]);
        out.entry_std_error[std::size_t(at[i])] = float(e.se / ps.area[i]);
        cols[at[i]] = e.j;
        values[at[i]++] = float(e.G / ps.area[i]);
      }
      variance[i] += (e.se / ps.area[i]) * (e.se / ps.area[i]);
      variance[j] += (e.se / ps.area[j]) * (e.se / ps.area[j]);
    }
  ff.row_std_error.resize(N);
  for (std::size_t i = 0; i < N; ++i) ff.row_std_error[i] = std::sqrt(variance[i]);
  return out;
}

}  // namespace radwalk
