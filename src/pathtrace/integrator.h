#pragma once
// PathIntegrator: unbiased estimates of radiance and irradiance on the original surfaces (the rendering
// equation), with three estimators of the direct light.
//
//   L(x, wo) = Le(x, wo) + int_{H^2} f(x, wo, wi) L(y(x, wi), -wi) |cos(theta_i)| dwi,      Le = E / pi on the
//   front side of an emitter (Lambertian), 0 elsewhere.                            Units: W / (m^2 sr).
//
// Integrators (IntegratorKind):
//   implicit  BSDF sampling only; emission counted when a path hits an emitter's front (Kajiya 1986).
//   nee       next-event estimation: at each non-delta vertex one emitter point y (light_sampler.h) and a shadow
//             ray; the area form f Le G / pdf_area with G = cos(theta_x) cos(theta_y) / |x - y|^2. Emission hit
//             by a BSDF-sampled direction is then counted only after a delta bounce (or by the camera ray).
//   mis       both, weighted by the power heuristic w_a = p_a^2 / (p_light^2 + p_bsdf^2), densities in solid
//             angle (Veach and Guibas 1995, "Optimally combining sampling techniques for Monte Carlo
//             rendering"). The default.
// Russian roulette: after rr_depth bounces a path survives with probability q = min(1, max channel of the
// throughput) and its throughput is divided by q, which keeps the estimate unbiased. There is no depth cap unless
// max_depth > 0; a cap drops every path with more than max_depth scattering events (a bias, reported as such).
//
// Surfaces: every model but the dielectric reflects on both sides; emission is on the front side only. Normals,
// points on patches and ray origins come from a SurfaceGeometry: the planar facets of the PatchSet
// (FacetGeometry) for a mesh, or exact curved surfaces.
// Reproducibility: the estimate is a pure function of the Rng passed in.
//
// Shadow rays are occlusion queries (Visibility::occluded) on the segment from the vertex to the light point,
// stopped short of the light's tangent plane (SurfaceGeometry::spawn_shadow_ray): the light sample counts when
// nothing lies between. Continuation rays are closest-hit queries.
// Paths as state machines (Path): a path waits for at most two rays at a time, the shadow ray of its last
// vertex's light sample and its continuation ray; advance() takes their answers and runs the path up to its next
// rays or its end. The shadow ray's answer only adds its contribution to L (it draws nothing), so deferring it
// to the continuation ray's batch changes no draw: a path's result is the same whether its rays are traced one
// at a time (radiance, irradiance) or with other paths' in batches (trace_batch: closest hits in packets of 16,
// occlusion in Embree's ray streams: the patch averages), up to a visibility whose answer for a ray depends on
// how it is traced (single ray or packet).
#include <string>
#include <vector>

#include "core/rng.h"
#include "pathtrace/bsdf.h"
#include "pathtrace/light_sampler.h"
#include "pathtrace/surface_geometry.h"
#include "visibility/visibility.h"

namespace radwalk {

struct PatchSet;

enum class IntegratorKind { implicit, nee, mis };
const char* to_string(IntegratorKind kind);
// "implicit", "nee" or "mis"; throws InputError otherwise.
IntegratorKind parse_integrator_kind(const std::string& name);

struct IntegratorOptions {
  IntegratorKind kind = IntegratorKind::mis;
  LightSelection light_selection = LightSelection::power;
  int rr_depth = 3;   // Russian roulette from this many scattering events on
  int max_depth = 0;  // 0: unbounded (unbiased); > 0: at most this many scattering events (biased)
};

// Work done, for rays-per-second figures.
struct PathCounters {
  long rays = 0;         // rays traced: closest-hit queries and shadow rays (occlusion queries), each one ray
  long shadow_rays = 0;  // of which shadow rays
  long vertices = 0;  // scattering events
  long escapes = 0;   // path rays that hit nothing (left the scene; shadow rays are not counted)
  void add(const PathCounters& o) {
    rays += o.rays;
    shadow_rays += o.shadow_rays;
    vertices += o.vertices;
    escapes += o.escapes;
  }
};

class PathIntegrator {
 public:
  // One path in flight: its state, its stream, the radiance gathered so far and the rays it waits for.
  class Path {
   public:
    Path() = default;
    bool done() const { return !tracing_ && !shadow_; }
    const Rgb& L() const { return L_; }  // the radiance gathered (the estimate, once done)
    Rng& rng() { return rng_; }

   private:
    friend class PathIntegrator;
    struct State {
      Rgb beta = Rgb::Ones();  // throughput: product of f |cos| / pdf, divided by the survival probabilities
      double pdf_prev = 0;     // solid-angle pdf of the last sampled direction
      bool delta_prev = true;  // the last direction came from a delta lobe or the camera: always count emission
      int depth = 0;           // scattering events so far
    } state_;
    Rgb L_ = Rgb::Zero();
    Rng rng_;
    Ray ray_;                            // the continuation ray, while tracing_
    bool tracing_ = false;
    Ray shadow_ray_;                     // the shadow ray (a segment), while shadow_
    bool shadow_ = false;
    Rgb shadow_L_ = Rgb::Zero();         // what it adds to L when the segment is not occluded
  };

  // Keeps references to patches, geometry and visibility (they must outlive it; visibility must trace the
  // surfaces geometry describes, for a mesh FacetGeometry(patches)); builds one Bsdf per patch.
  PathIntegrator(const PatchSet& patches, const SurfaceGeometry& geometry, const Visibility& visibility,
                 const IntegratorOptions& options = {});

  // Radiance arriving at ray.origin along -ray.direction: L(y, -d) for the first hit y (0 on a miss).
  Rgb radiance(const Ray& ray, Rng& rng, PathCounters& counters) const;

  // Irradiance on the front of patch i at its point x: E_irr(x) = int_{H^2(n_i(x))} L_in(x, w) cos(theta) dw
  // (W/m^2). Estimated as pi times the radiance a white Lambertian at x would reflect, so one cosine-sampled
  // direction scores pi L_in (implicit), and NEE/MIS add the direct part from light samples.
  Rgb irradiance(PatchIndex i, const Vec3& x, Rng& rng, PathCounters& counters) const;

  // The path of irradiance(i, x, rng) started: what irradiance estimates is pi L() once it is done.
  Path start_irradiance(PatchIndex i, const Vec3& x, const Rng& rng, PathCounters& counters) const;
  // Traces the rays of paths[0 .. n) in one batch (Visibility's batch intersect: packets of 16 rays) and
  // advances each path.
  void trace_batch(Path* const* paths, std::size_t n, PathCounters& counters) const;

  const IntegratorOptions& options() const { return options_; }
  const LightSampler& lights() const { return lights_; }
  const SurfaceGeometry& geometry() const { return geometry_; }
  const Bsdf& bsdf(PatchIndex i) const;

 private:
  // The vertex at x (on `patch`, normal n, towards wo_world): its light sample (a shadow ray the path then
  // waits for) and its continuation (true: path.ray_ set and waited for; false: the path ends there).
  bool scatter(const Bsdf& bsdf, PatchIndex patch, const Vec3& x, const Vec3& n, const Vec3& wo_world, Path& path,
               PathCounters& counters) const;
  // Takes the answers to the rays the path waited for (shadow_blocked if it waited for a shadow ray, hit if for a
  // continuation) and runs it up to its next rays or its end.
  void advance(Path& path, bool shadow_blocked, const Hit& hit, PathCounters& counters) const;
  // Runs a path to its end, its rays traced one at a time.
  void run_alone(Path& path, PathCounters& counters) const;

  const PatchSet& patches_;
  const SurfaceGeometry& geometry_;
  const Visibility& visibility_;
  IntegratorOptions options_;
  LightSampler lights_;
  std::vector<Bsdf> bsdfs_;  // per patch (rho is per patch)
};

}  // namespace radwalk
