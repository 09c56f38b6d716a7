#pragma once
// Validation of a Mesh before any computation (policy table: meshes/README.md, section "Validation").
//
// validate_mesh either throws InputError with one line "FILE:LINE: face F: what is wrong" (the first error found;
// face F is the 0-based input face, LINE its source line) or repairs in place and appends one-line warnings
// naming the face and line to mesh.warnings (at most `max_warnings_per_kind` per kind, then one summary line).
//
// Errors (refused): no faces; non-finite coordinate; face with fewer than 3 corners; vertex index out of range;
//   triangle with a repeated vertex (or two corners at the same point); quad with two repeats or a repeat across a
//   diagonal; degenerate face (area <= degenerate_area * D^2, D = diagonal of the scene's bounding box);
//   non-planar quad (quad_nonplanarity > planar_error); non-convex quad (quad_min_turn_sine < -convex_sine);
//   duplicate face (same welded corners, in either orientation); material index out of range; reflectance Kd
//   outside [0, 1) or emission Ke negative or not finite, for a material some face uses.
// Repaired with a warning: quad with one vertex repeated at adjacent corners -> triangle; face without material
//   -> material "radwalk_default" (rho 0.5, no emission).
// Warnings only: slightly non-planar quad (planar_clean < nonplanarity <= planar_error); non-manifold edge (3+
//   faces); non-manifold vertex (faces around it form 2+ fans); neighbours with inconsistent orientation (flipped
//   face); a non-diffuse material (the radiosity solvers use Kd only); no emitter.
#include "mesh/mesh.h"

namespace radwalk {

struct ValidationTolerances {
  double degenerate_area = 1e-10;  // relative to the squared bounding-box diagonal
  double planar_clean = 2e-3;      // quad_nonplanarity up to this passes silently (measured Cornell box: 1.02e-3)
  double planar_error = 1e-2;      // above this a quad is refused
  double convex_sine = 1e-9;       // turning sine below -convex_sine makes a quad non-convex
  int max_warnings_per_kind = 10;
  // The scene's extent (bounding-box diagonal, in mesh units) must lie in [min_extent, max_extent]: rays are
  // traced in single precision, where a scene much larger (squared lengths overflow) or much smaller (they
  // underflow) than these loses every ray without a visible error.
  double min_extent = 1e-8;
  double max_extent = 1e16;
  // Coordinates far from the origin relative to the scene (max |coordinate| / extent above this) leave too few
  // float digits for the scene's detail: a warning (move the origin into the scene).
  double max_offset_ratio = 1e4;
  // Repairs (dropping zero-area faces, splitting bent or concave quads) become refusals.
  bool strict = false;
};

void validate_mesh(Mesh& mesh, const ValidationTolerances& tolerances = {});

}  // namespace radwalk
