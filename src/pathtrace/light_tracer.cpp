#include "pathtrace/light_tracer.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/sampling.h"
#include "core/timer.h"
#include "patch/patch_set.h"
#include "pathtrace/facet_geometry.h"
#include "pathtrace/russian_roulette.h"

namespace radwalk {

namespace {
constexpr long kChunk = 4096;              // particles per work item
constexpr std::size_t kBatch = 32;         // work items whose patch tallies are held in memory at once
constexpr std::size_t kImageBatch = 8;     // the same for image tallies (one entry per pixel)

struct Tally {
  std::vector<Rgb> sum, sum2;
  PathCounters counters;
  explicit Tally(std::size_t n = 0) : sum(n, Rgb::Zero()), sum2(n, Rgb::Zero()) {}
  void clear() {
    std::fill(sum.begin(), sum.end(), Rgb::Zero());
    std::fill(sum2.begin(), sum2.end(), Rgb::Zero());
    counters = {};
  }
};

// One particle from emission to absorption. Calls visit.emitted(ls, w0) at the emission point and
// visit.arrived(hit, x, bsdf, frame, wo, w) at every surface it reaches before the depth cap, with w the flux it
// carries there and frame the shading frame facing wo (the direction back along the path).
template <class Visitor>
void trace_particle(const PatchSet& patches, const Visibility& visibility, const PathIntegrator& integrator,
                    const LightTraceOptions& options, Rng& rng, Visitor& visit, PathCounters& counters) {
  const LightSampler& lights = integrator.lights();
  const SurfaceGeometry& geometry = integrator.geometry();
  // Emission: emitter by power, uniform point, cosine direction about the front normal.
  const double us = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
  const LightSample ls = lights.sample(us, u1, u2);
  const Rgb w0 = patches.area[ls.patch] * patches.E[ls.patch] / lights.pmf(ls.patch);
  visit.emitted(ls, w0);
  const double v1 = rng.uniform(), v2 = rng.uniform();
  Vec3 dir = Frame(ls.normal).to_world(sample_cosine_hemisphere(v1, v2));
  Ray ray = geometry.spawn_ray(ls.patch, ls.point, dir);
  Rgb beta = Rgb::Ones();  // w = w0 * beta
  int depth = 0;           // bounces so far; the arrival at depth d is the (d+1)-th reflection
  for (;;) {
    const Hit hit = visibility.intersect(ray);
    ++counters.rays;
    if (hit.missed()) {
      ++counters.escapes;
      return;
    }
    const Vec3 x = ray.origin + hit.t * ray.direction;
    const Bsdf& bsdf = integrator.bsdf(hit.patch);
    const Vec3 n_front = geometry.normal(hit.patch, x);
    // The back of a one-sided face absorbs (patch/patch_set.h, "Sides"); a dielectric scatters from both sides.
    if (!hit.front && bsdf.is_opaque()) return;
    const Frame frame(n_front);
    const Vec3 wo = frame.to_local(-ray.direction);
    visit.arrived(hit, x, bsdf, frame, wo, Rgb(w0 * beta));
    // Scatter by the patch's BSDF.
    const double b1 = rng.uniform(), b2 = rng.uniform(), bc = rng.uniform();
    const auto bs = bsdf.sample(wo, b1, b2, bc);
    ++counters.vertices;
    if (!bs || !(bs->weight > 0).any()) return;
    beta *= bs->weight;
    ++depth;
    if (depth >= options.rr_depth && !survive_russian_roulette(beta, rng)) return;
    if (options.max_depth > 0 && depth >= options.max_depth) return;  // the cap: no ray that could not score
    dir = frame.to_world(bs->wi);
    ray = geometry.spawn_ray(hit.patch, x, dir);
  }
}

// Scores of one particle per bin (patch or pixel); repeated visits are merged before squaring.
struct Scores {
  std::vector<std::pair<std::size_t, Rgb>> entries;
  void add(std::size_t bin, const Rgb& s) {
    auto it = std::find_if(entries.begin(), entries.end(), [&](const auto& e) { return e.first == bin; });
    if (it == entries.end())
      entries.emplace_back(bin, s);
    else
      it->second += s;
  }
};

// Patch tally: front arrivals score rho_i w / A_i.
struct PatchTally {
  const PatchSet& patches;
  Scores& scores;
  void emitted(const LightSample&, const Rgb&) {}
  void arrived(const Hit& hit, const Vec3&, const Bsdf&, const Frame&, const Vec3&, const Rgb& w) {
    const auto i = static_cast<std::size_t>(hit.patch);
    if (hit.front && (patches.rho[i] > 0).any()) scores.add(i, patches.rho[i] * w / patches.area[i]);
  }
};

// Camera splat: each vertex connected to the pinhole, I_pixel += w f |cos_y| cos_c W / d^2 (emission point:
// w0 Le/E = w0 / pi in place of w f).
struct CameraSplat {
  const SurfaceGeometry& geometry;
  const Visibility& visibility;
  const PinholeCamera& camera;
  Scores& scores;
  PathCounters& counters;
  void connect(PatchIndex patch, const Vec3& x, const Vec3& wc, double d, const Rgb& value) {
    const auto film = camera.project(x);
    if (!film) return;
    Ray shadow = geometry.spawn_ray(patch, x, wc);
    shadow.tmax = d;
    ++counters.rays;
    if (visibility.occluded(shadow)) return;
    const double cos_c = -wc.dot(camera.forward());
    const double W = camera.importance(-wc);
    const auto px = static_cast<std::size_t>(film->x()), py = static_cast<std::size_t>(film->y());
    scores.add(py * static_cast<std::size_t>(camera.width()) + px, value * (W * cos_c / (d * d)));
  }
  void emitted(const LightSample& ls, const Rgb& w0) {
    const Vec3 dc = camera.position() - ls.point;
    const double d = dc.norm();
    const Vec3 wc = dc / d;
    const double cos_y = wc.dot(ls.normal);
    if (cos_y > 0) connect(ls.patch, ls.point, wc, d, w0 * (kInvPi * cos_y));
  }
  void arrived(const Hit& hit, const Vec3& x, const Bsdf& bsdf, const Frame& frame, const Vec3& wo, const Rgb& w) {
    if (bsdf.is_delta()) return;
    const Vec3 dc = camera.position() - x;
    const double d = dc.norm();
    const Vec3 wc = dc / d;
    const Vec3 wc_local = frame.to_local(wc);
    const Rgb f = bsdf.f(wo, wc_local);
    if ((f > 0).any()) connect(hit.patch, x, wc, d, w * f * std::abs(wc_local.z()));
  }
};

// Runs `particles` particles in fixed chunks; trace(k, rng, scores, counters) fills one particle's scores.
// Per-bin sums of scores / scale and of their squares are combined in chunk order (bit-identical for any thread
// count); scale is a power of two (moment_scale of the largest emission), so the division is exact.
template <class Trace>
void run_particles(std::size_t bins, const LightTraceOptions& options, std::size_t batch, const char* label,
                   double scale, Tally& total, Trace&& trace) {
  const double inverse_scale = 1 / scale;
  const auto chunks = static_cast<std::size_t>((options.particles + kChunk - 1) / kChunk);
  std::vector<Tally> tallies(std::min(chunks, batch), Tally(bins));
  std::optional<Progress> progress;
  if (options.progress) progress.emplace(label, chunks);
  const RngFamily particles(options.seed, StreamDomain::light_particle, 0);
  // Batches of chunks: chunks in parallel, each into its own tally, then added in chunk order.
  for (std::size_t b0 = 0; b0 < chunks; b0 += batch) {
    const std::size_t b1 = std::min(chunks, b0 + batch);
    parallel_for(
        b1 - b0,
        [&](std::size_t c) {
          Tally& t = tallies[c];
          t.clear();
          Scores scores;
          const long k0 = static_cast<long>(b0 + c) * kChunk;
          const long k1 = std::min(options.particles, k0 + kChunk);
          for (long k = k0; k < k1; ++k) {
            Rng rng = particles.stream(static_cast<std::uint64_t>(k));
            scores.entries.clear();
            trace(rng, scores, t.counters);
            for (const auto& [i, s] : scores.entries) {
              const Rgb y = s * inverse_scale;
              t.sum[i] += y;
              t.sum2[i] += y * y;
            }
          }
          if (progress) progress->advance(1);
        },
        1);
    for (std::size_t c = 0; c < b1 - b0; ++c) {
      for (std::size_t i = 0; i < bins; ++i) {
        total.sum[i] += tallies[c].sum[i];
        total.sum2[i] += tallies[c].sum2[i];
      }
      total.counters.add(tallies[c].counters);
    }
  }
  if (progress) progress->finish();
}

}  // namespace

Solution light_trace_patches(const PatchSet& patches, const Visibility& visibility,
                             const LightTraceOptions& options) {
  return light_trace_patches(patches, FacetGeometry(patches), visibility, options);
}

Solution light_trace_patches(const PatchSet& patches, const SurfaceGeometry& geometry, const Visibility& visibility,
                             const LightTraceOptions& options) {
  if (options.particles < 2)
    throw InputError("light tracer: particles must be >= 2 (got " + std::to_string(options.particles) + ")");
  const Timer timer;
  IntegratorOptions io;
  io.kind = IntegratorKind::implicit;
  // BSDFs, geometry and the power-proportional light choice.
  const PathIntegrator integrator(patches, geometry, visibility, io);
  const std::size_t n = patches.size();

  Tally total(n);
  const double scale = moment_scale(patches.max_emission());
  if (!integrator.lights().empty())
    run_particles(n, options, kBatch, "light tracing", scale, total, [&](Rng& rng, Scores& scores, PathCounters& c) {
      PatchTally visit{patches, scores};
      trace_particle(patches, visibility, integrator, options, rng, visit, c);
    });

  // Mean and unbiased per-particle variance of each patch's score, scaled back (var infinite only when it does not
  // fit a double).
  Solution sol;
  sol.method = "lighttrace";
  const auto rows = static_cast<Eigen::Index>(n);
  sol.B.resize(rows, 3);
  sol.B_se.resize(rows, 3);
  sol.var.resize(rows, 3);
  const double m = static_cast<double>(options.particles);
  for (std::size_t i = 0; i < n; ++i) {
    const auto [mean, var] = mean_and_variance(total.sum[i], total.sum2[i], m);
    const auto r = static_cast<Eigen::Index>(i);
    sol.B.row(r) = (patches.E[i] + mean * scale).transpose();
    sol.var.row(r) = (var * scale * scale).transpose();
    sol.B_se.row(r) = ((var / m).sqrt() * scale).transpose();
  }
  sol.status = SolveStatus::converged;
  sol.walks = options.particles;
  sol.steps = total.counters.vertices;
  sol.seconds = timer.seconds();
  sol.message = "light traced " + std::to_string(options.particles) + " particles";
  if (options.max_depth > 0)
    sol.message += " (biased: paths capped at " + std::to_string(options.max_depth) + " bounces)";
  sol.info["rays"] = static_cast<double>(total.counters.rays);
  sol.info["escapes"] = static_cast<double>(total.counters.escapes);
  sol.info["rays_per_second"] = sol.seconds > 0 ? static_cast<double>(total.counters.rays) / sol.seconds : 0.0;
  return sol;
}

}  // namespace radwalk

namespace radwalk {

RenderResult light_trace_image(const PatchSet& patches, const Visibility& visibility, const Camera& camera,
                               int width, int height, const LightTraceOptions& options) {
  if (options.particles < 2)
    throw InputError("light tracer: particles must be >= 2 (got " + std::to_string(options.particles) + ")");
  const Timer timer;
  const PinholeCamera pinhole(camera, width, height);
  IntegratorOptions io;
  io.kind = IntegratorKind::implicit;
  const FacetGeometry facets(patches);
  const PathIntegrator integrator(patches, facets, visibility, io);
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  Tally total(pixels);
  const double scale = moment_scale(patches.max_emission());
  if (!integrator.lights().empty())
    run_particles(pixels, options, kImageBatch, "light tracing image", scale, total,
                  [&](Rng& rng, Scores& scores, PathCounters& c) {
                    CameraSplat visit{integrator.geometry(), visibility, pinhole, scores, c};
                    trace_particle(patches, visibility, integrator, options, rng, visit, c);
                  });
  RenderResult result;
  result.mean = RgbImage(width, height);
  result.se = RgbImage(width, height);
  const double m = static_cast<double>(options.particles);
  for (std::size_t k = 0; k < pixels; ++k) {
    const auto [mean, var] = mean_and_variance(total.sum[k], total.sum2[k], m);
    result.mean.pixels[k] = mean * scale;
    result.se.pixels[k] = (var / m).sqrt() * scale;
  }
  result.spp = options.particles;
  result.rays = total.counters.rays;
  result.vertices = total.counters.vertices;
  result.seconds = timer.seconds();
  return result;
}

}  // namespace radwalk
