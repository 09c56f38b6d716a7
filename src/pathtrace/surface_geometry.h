#pragma once
// SurfaceGeometry: the shape of the surfaces the path tracer walks on, patch by patch.
//
// The PatchSet gives what is constant over a patch (rho, E, material, and area A_i, which must be the true area of
// the surface of patch i); SurfaceGeometry gives what varies over it: the normal at a point, uniform points on it,
// and rays leaving it. The path tracer's estimators are written against this interface, so they run on the planar
// facets of a mesh (FacetGeometry, the default) and on exact curved surfaces (an analytic sphere in the tests, where
// the rendering equation has a closed-form solution that no polyhedron has).
// A Visibility for the same scene answers ray queries; the two must describe the same surfaces.
#include "core/types.h"
#include "visibility/ray_offset.h"
#include "visibility/visibility.h"

namespace radwalk {

class SurfaceGeometry {
 public:
  virtual ~SurfaceGeometry() = default;

  // The unit front normal n_i(x) of patch i at the point x on it (emission leaves by the front).
  virtual Vec3 normal(PatchIndex i, const Vec3& x) const = 0;

  // A point uniformly distributed over the surface of patch i (area density 1 / A_i) from u in [0, 1)^2.
  virtual Vec3 sample_point(PatchIndex i, double u1, double u2) const = 0;

  // A ray leaving the point x on patch i along the unit direction d, its origin moved off the surface to the side
  // d leaves by, so that tracing it does not find patch i again at t ~ 0.
  virtual Ray spawn_ray(PatchIndex i, const Vec3& x, const Vec3& d) const = 0;

  // A shadow ray: leaves the point x on patch i along the unit direction w = (y - x) / r, r = |y - x|, towards the
  // point y of another surface (front normal n_y there), as a segment that stops before y's tangent plane
  // (visibility/ray_offset.h, stop_before_plane, margin 0 here; an override may add its offset's scale), so that
  // Visibility::occluded asks whether anything lies between x and y, not whether y's own surface is there.
  // tmax <= 0: no segment to test (a grazing pair).
  virtual Ray spawn_shadow_ray(PatchIndex i, const Vec3& x, const Vec3& w, double r, const Vec3& y,
                               const Vec3& n_y) const {
    return stop_before_plane(spawn_ray(i, x, w), r, y, n_y, 0.0);
  }

  // Whether a point of patch i can see other points of patch i. False for a planar patch (next-event estimation
  // then skips light samples on the receiver's own patch: they contribute exactly zero); true on a concave
  // curved patch, where such samples carry light.
  virtual bool sees_itself(PatchIndex i) const = 0;

  // A hint with no effect on any value: asks for the memory that normal(i, .) and spawn_ray(i, ...) read, ahead
  // of the calls (at large N each is a cache miss). Does nothing unless overridden.
  virtual void prefetch(PatchIndex) const {}

};

}  // namespace radwalk
