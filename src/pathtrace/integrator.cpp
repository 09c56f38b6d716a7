#include "pathtrace/integrator.h"

#include <cmath>

#include "core/error.h"
#include "core/sampling.h"
#include "patch/patch_set.h"
#include "pathtrace/russian_roulette.h"

namespace radwalk {

namespace {
double power_heuristic(double pa, double pb) {
  const double a2 = pa * pa, b2 = pb * pb;
  return a2 + b2 > 0 ? a2 / (a2 + b2) : 0.0;
}
}  // namespace

const char* to_string(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::implicit:
      return "implicit";
    case IntegratorKind::nee:
      return "nee";
    case IntegratorKind::mis:
      return "mis";
  }
  return "?";
}

IntegratorKind parse_integrator_kind(const std::string& name) {
  if (name == "implicit") return IntegratorKind::implicit;
  if (name == "nee") return IntegratorKind::nee;
  if (name == "mis") return IntegratorKind::mis;
  throw InputError("unknown path tracing integrator '" + name + "' (expected implicit, nee or mis)");
}

PathIntegrator::PathIntegrator(const PatchSet& patches, const SurfaceGeometry& geometry,
                               const Visibility& visibility, const IntegratorOptions& options)
    : patches_(patches),
      geometry_(geometry),
      visibility_(visibility),
      options_(options),
      lights_(patches, geometry, options.light_selection) {
  if (options.rr_depth < 0) throw InputError("path tracer: rr_depth must be >= 0");
  if (options.max_depth < 0) throw InputError("path tracer: max_depth must be >= 0 (0 = no cap)");
  bsdfs_.reserve(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const std::int32_t m = patches.material.empty() ? -1 : patches.material[i];
    bsdfs_.push_back(m >= 0 && static_cast<std::size_t>(m) < patches.materials.size()
                         ? make_bsdf(patches.materials[m], patches.rho[i])
                         : Bsdf(Lambertian(patches.rho[i])));
  }
}

const Bsdf& PathIntegrator::bsdf(PatchIndex i) const { return bsdfs_[static_cast<std::size_t>(i)]; }

bool PathIntegrator::scatter(const Bsdf& bsdf, PatchIndex patch, const Vec3& x, const Vec3& n,
                             const Vec3& wo_world, Path& path, PathCounters& counters) const {
  Path::State& state = path.state_;
  Rng& rng = path.rng_;
  const Frame frame(n);
  const Vec3 wo = frame.to_local(wo_world);
  ++counters.vertices;

  // Next-event estimation: one point on the emitters, a shadow ray, the area form weighted for MIS. The shadow
  // ray is traced with the continuation ray; if nothing occludes its segment, shadow_L_ is added to L.
  if (options_.kind != IntegratorKind::implicit && !bsdf.is_delta() && !lights_.empty()) {
    const double us = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const LightSample ls = lights_.sample(us, u1, u2);
    if (ls.patch != patch || geometry_.sees_itself(patch)) {
      const Vec3 d = ls.point - x;
      const double dist2 = d.squaredNorm();
      const double dist = std::sqrt(dist2);
      const Vec3 wi_world = d / dist;
      const double cos_y = -wi_world.dot(ls.normal);
      if (cos_y > 0 && dist > 0) {
        const Vec3 wi = frame.to_local(wi_world);
        const Rgb f = bsdf.f(wo, wi);
        if ((f > 0).any()) {
          path.shadow_ray_ = geometry_.spawn_shadow_ray(patch, x, wi_world, dist, ls.point, ls.normal);
          path.shadow_ = path.shadow_ray_.tmax > 0;
        }
        if (path.shadow_) {
          const double p_light = ls.pdf_area * dist2 / cos_y;
          const double w = options_.kind == IntegratorKind::mis ? power_heuristic(p_light, bsdf.pdf(wo, wi)) : 1.0;
          path.shadow_L_ = state.beta * f * (std::abs(wi.z()) * w / p_light) * ls.Le;
        }
      }
    }
  }

  // BSDF sampling of the continuation direction.
  const double u1 = rng.uniform(), u2 = rng.uniform(), uc = rng.uniform();
  const auto s = bsdf.sample(wo, u1, u2, uc);
  if (!s || !(s->weight > 0).any()) return false;
  state.beta *= s->weight;
  state.pdf_prev = s->pdf;
  state.delta_prev = s->delta;
  ++state.depth;

  if (state.depth >= options_.rr_depth && !survive_russian_roulette(state.beta, rng)) return false;
  path.ray_ = geometry_.spawn_ray(patch, x, frame.to_world(s->wi));
  return true;
}

void PathIntegrator::advance(Path& path, bool shadow_blocked, const Hit& hit, PathCounters& counters) const {
  // The last vertex's light sample first (the order in which L adds the terms: this vertex's, then the next's).
  if (path.shadow_) {
    path.shadow_ = false;
    if (!shadow_blocked) path.L_ += path.shadow_L_;
  }
  if (!path.tracing_) return;
  path.tracing_ = false;
  const Ray& ray = path.ray_;
  Path::State& state = path.state_;
  if (hit.missed()) {
    ++counters.escapes;
    return;
  }
  const auto j = static_cast<std::size_t>(hit.patch);
  const Vec3 x = ray.origin + hit.t * ray.direction;
  const Vec3 n_front = geometry_.normal(hit.patch, x);

  // Emission from the front of an emitter, weighted against next-event estimation.
  if (hit.front && (patches_.E[j] > 0).any()) {
    const Rgb Le = patches_.E[j] * kInvPi;
    if (options_.kind == IntegratorKind::implicit || state.delta_prev) {
      path.L_ += state.beta * Le;
    } else if (options_.kind == IntegratorKind::mis) {
      const double cos_y = -ray.direction.dot(n_front);
      const double p_light = lights_.pdf_area(hit.patch) * hit.t * hit.t / cos_y;
      path.L_ += state.beta * power_heuristic(state.pdf_prev, p_light) * Le;
    }
  }
  if (options_.max_depth > 0 && state.depth >= options_.max_depth) return;

  // The back of a one-sided face absorbs (a two-sided face's back is a patch of its own, hit from its front);
  // a dielectric is an interface and scatters from both sides with its front normal.
  const Bsdf& bsdf = bsdfs_[j];
  if (!hit.front && bsdf.is_opaque()) return;
  const Vec3 wo_world = -ray.direction;
  path.tracing_ = scatter(bsdf, hit.patch, x, n_front, wo_world, path, counters);
}

void PathIntegrator::run_alone(Path& path, PathCounters& counters) const {
  while (!path.done()) {
    bool blocked = false;
    Hit hit;
    if (path.shadow_) {
      ++counters.rays;
      ++counters.shadow_rays;
      blocked = visibility_.occluded(path.shadow_ray_);
    }
    if (path.tracing_) {
      ++counters.rays;
      hit = visibility_.intersect(path.ray_);
    }
    advance(path, blocked, hit, counters);
  }
}

void PathIntegrator::trace_batch(Path* const* paths, std::size_t n, PathCounters& counters) const {
  // The paths' shadow rays (occlusion) and continuation rays (closest hit), each in path order.
  constexpr std::size_t kMaxBatch = 32;
  Ray shadow[kMaxBatch], rays[kMaxBatch];
  bool blocked[kMaxBatch];
  Hit hits[kMaxBatch];
  for (std::size_t base = 0; base < n; base += kMaxBatch) {
    const std::size_t end = std::min(n, base + kMaxBatch);
    std::size_t ms = 0, mc = 0;
    for (std::size_t k = base; k < end; ++k) {
      if (paths[k]->shadow_) shadow[ms++] = paths[k]->shadow_ray_;
      if (paths[k]->tracing_) rays[mc++] = paths[k]->ray_;
    }
    if (ms > 0) visibility_.occluded(shadow, blocked, ms);
    if (mc > 0) visibility_.intersect(rays, hits, mc);
    counters.rays += static_cast<long>(ms + mc);
    counters.shadow_rays += static_cast<long>(ms);
    // A hint, no effect on any value: the records of the patches the continuation rays hit (read by advance),
    // asked for all at once so that their cache misses overlap.
    for (std::size_t c = 0; c < mc; ++c) {
      const PatchIndex j = hits[c].patch;
      if (j < 0) continue;
      __builtin_prefetch(&patches_.E[static_cast<std::size_t>(j)]);
      __builtin_prefetch(&bsdfs_[static_cast<std::size_t>(j)]);
      geometry_.prefetch(j);
    }
    ms = mc = 0;
    for (std::size_t k = base; k < end; ++k) {
      Path& path = *paths[k];
      bool is_blocked = false;
      Hit hit;
      if (path.shadow_) is_blocked = blocked[ms++];
      if (path.tracing_) hit = hits[mc++];
      advance(path, is_blocked, hit, counters);
    }
  }
}

Rgb PathIntegrator::radiance(const Ray& ray, Rng& rng, PathCounters& counters) const {
  Path path;
  path.rng_ = rng;
  path.ray_ = ray;
  path.tracing_ = true;
  run_alone(path, counters);
  rng = path.rng_;
  return path.L_;
}

PathIntegrator::Path PathIntegrator::start_irradiance(PatchIndex i, const Vec3& x, const Rng& rng,
                                                      PathCounters& counters) const {
  // A white Lambertian vertex at x facing the patch's front: reflected radiance = E_irr / pi.
  static const Bsdf white(Lambertian(Rgb::Ones()));
  const Vec3 n = geometry_.normal(i, x);
  Path path;
  path.rng_ = rng;
  path.tracing_ = scatter(white, i, x, n, n, path, counters);
  return path;
}

Rgb PathIntegrator::irradiance(PatchIndex i, const Vec3& x, Rng& rng, PathCounters& counters) const {
  Path path = start_irradiance(i, x, rng, counters);
  run_alone(path, counters);
  rng = path.rng_;
  return kPi * path.L_;
}

}  // namespace radwalk
