#pragma once
// Validation of a Mesh before any computation (policy table: meshes/README.md, section "Validation").
//
// validate_mesh collects every finding of the scene (finding.h) into mesh.findings, after the reader's own
// (unknown materials, bad indices, polygon repairs): refusals (errors), repairs done in place, warnings and notes,
// each naming the input face, line, object, group and material. Faces with an error are left out of the later
// steps (that need their corners or area) but every other face is still checked, so one run reports every defect.
// Then mesh.warnings is set to the repairs and warnings as lines grouped by kind (validation_lines; the notes are
// only in mesh.findings), and if any
// finding is an error, MeshRefused (an InputError whose one-line what() is the first error and the count of the
// others) is thrown with all of them.
//
// Errors (refused): no faces; non-finite coordinate; face with fewer than 3 corners; vertex index out of range;
//   scene too large or too small for single precision (the later steps are skipped); and with strict:
//   degenerate face (area <= degenerate_area * D^2, D = diagonal of the scene's bounding box), non-planar quad
//   (quad_nonplanarity > planar_error), non-convex quad (quad_min_turn_sine < -convex_sine), area-ambiguous quad
//   (quad area ambiguity > area_ambiguity, below); self-intersecting quad (bow-tie); repeated corners; duplicate
//   faces; always: a bow-tie off its plane that neither diagonal splits; material index out of range; reflectance Kd outside [0, 1) or
//   emission Ke negative, not finite or above 1e300, for a material some face uses; a used material without
//   reflectance (Material::reflectance_missing: an STL solid, a VTK surface without rho), naming the --set that
//   gives one.
// Repaired (refused with strict where said above): repeated corners (same index or same point): the outline split
//   at its repeats into loops (repeated_corners.h, area as drawn kept), loops of fewer than 3 corners dropped (a quad
//   with one vertex repeated at adjacent corners -> triangle; a triangle with a repeat has no area and is dropped);
//   duplicate faces (same welded corners): back to back -> one face with a two-sided copy of its material (a front
//   and a back patch, docs/two-sided.md), facing the same way -> the later dropped;
//   face without material -> material "radwalk_default" (rho 0.5, no emission); degenerate face dropped;
//   non-planar, non-convex or area-ambiguous quad split into two triangles along the better diagonal; a planar
//   self-intersecting quad (a bow-tie) split at its crossing into its two lobes (polygon_crossings.h: a new vertex
//   there, both facing along the quad's dominant normal); a folded quad off its plane (vector area below half its
//   area, a bow-tie in projection) split along the diagonal whose two triangles both have area and turn the Newell
//   normal's way, so that they do not overlap seen along it (the two triangles are its area as drawn); refused
//   when neither diagonal gives such triangles.
// Orientation (orient_shells.h, tolerances.orient): faces flipped to agree with their shells and closed shells
//   turned outward (the room inward), except in a run's patches as radwalk wrote them (Mesh::as_written: its own
//   .vtp and .obj), which keep their orientation and sides under the defaults (orient not given, open shells auto;
//   an orientation asked for, tolerances.orient_given, applies with a note "faces as written oriented again"):
//   the flips are one warning with the count, area and objects; non-orientable shells a warning each; open shells (not emitters alone) a note each, suggesting two-sided faces (an open room, the
//   Cornell box, is one: harmless where no light reaches the backs, which power_balance measures).
// Warnings: slightly non-planar quad (planar_clean < nonplanarity <= planar_error); coplanar faces that overlap
//   with positive area facing the same way (coplanar_overlaps.h: both faces and the shared area named; back to back
//   they are a contact, a block's bottom on a floor, which patching cuts along); non-manifold edge (3+
//   faces); non-manifold vertex (faces around it form 2+ fans, joined across T-junctions); neighbours with
//   inconsistent orientation (flipped face); a non-diffuse material (the radiosity solvers use Kd only); no
//   emitter; a scene far from the origin.
// Notes: T-junctions (t_junctions.h), named at the T point: harmless for the constant-radiosity solve; open shells.
//
// The area ambiguity of a quad (face_geometry.h): its bilinear surface (where its patches lie) and its two
// triangulations differ in area by at most ambiguity x area, so a validated quad's patches add up to its area
// within area_ambiguity.
#include <string>

#include "mesh/mesh.h"
#include "mesh/orient_shells.h"

namespace radwalk {

// The sides of the faces of open shells (orient_shells.h; docs/units-and-formats.md, "Orientation"):
//   two_sided: every open shell's faces get two-sided copies of their materials (a front and a back patch);
//   one_sided: the faces stay as the file has them;
//   automatic (the default): the choice that loses least. In a scene enclosed by a closed shell (a room, found as
//     orient_shells finds it) no light escapes, so the light interreflected in the room reaches the backs of the
//     open shells in it, which a one-sided face absorbs entirely and a two-sided back reflects by its rho:
//     two-sided, which never loses more. In a scene that no closed shell encloses (an open box such as the
//     Cornell box, whose walls are themselves an open shell facing the void with their backs) one-sided, as the
//     file has them: the open room's backs see no light, and the open shells are noted with the suggestion to
//     make them two-sided.
enum class OpenShellSides { automatic, one_sided, two_sided };

// "auto", "one-sided", "two-sided".
const char* open_shell_sides_name(OpenShellSides sides);
// The value of a name above; InputError naming the valid ones for another.
OpenShellSides parse_open_shell_sides(const std::string& name);

struct ValidationTolerances {
  double degenerate_area = 1e-10;  // relative to the squared bounding-box diagonal
  double planar_clean = 2e-3;      // quad_nonplanarity up to this passes silently (measured Cornell box: 1.02e-3)
  double planar_error = 1e-2;      // above this a quad is refused
  double convex_sine = 1e-9;       // turning sine below -convex_sine makes a quad non-convex
  // Above this area ambiguity (face_geometry.h quad_area_ambiguity) a quad is split (refused with strict). A fat
  // quad at the planarity limit has 8e-4, the bundled Cornell box at most 4.8e-6; the fuzz finding "v 0 1 0 /
  // v 1 0 0 / v 343 548.8 332 / v 343 548.8 227" (a thin quad) 1.3e-2 with a bend of only 0.74 %.
  double area_ambiguity = 2e-3;
  int max_warnings_per_kind = 10;  // lines per kind in mesh.warnings (validation_lines)
  // The scene's extent (bounding-box diagonal, in mesh units) must lie in [min_extent, max_extent]: rays are
  // traced in single precision, where a scene much larger (squared lengths overflow) or much smaller (they
  // underflow) than these loses every ray without a visible error.
  double min_extent = 1e-8;
  double max_extent = 1e16;
  // Coordinates far from the origin relative to the scene (max |coordinate| / extent above this) leave too few
  // float digits for the scene's detail: a warning (move the origin into the scene).
  double max_offset_ratio = 1e4;
  // Orientation of the shells (orient_shells.h): outward by default; the flips are one warning.
  OrientMode orient = OrientMode::outward;
  // The orientation was asked for (--orient given), not left at its default: it then applies to a run's patches
  // as radwalk wrote them (Mesh::as_written) too, with a note saying so; left at its default it keeps them.
  bool orient_given = false;
  // The sides of open shells' faces (not emitters alone; --open-shells, OpenShellSides above).
  OpenShellSides open_shells = OpenShellSides::automatic;
  // Repairs (dropping zero-area faces, splitting bent or concave quads, repeated corners, duplicate faces) become
  // refusals.
  bool strict = false;
};

// The largest emitted radiance Ke a material may hold (validate_mesh refuses more): E = pi Ke must stay finite and
// leave room for the radiosity it drives.
constexpr double kMaxKe = 1e300;

void validate_mesh(Mesh& mesh, const ValidationTolerances& tolerances = {});

// The repairs and warnings among `findings` as lines grouped by kind, at most per_kind of each and then
// "FILE: KIND: N more (T in all)" (finding.h grouped_lines).
std::vector<std::string> validation_lines(const std::vector<Finding>& findings, std::size_t per_kind);
// The notes among `findings` (how the file was read, e.g. a file radwalk wrote oriented again), grouped as above.
std::vector<std::string> validation_notes(const std::vector<Finding>& findings, std::size_t per_kind);

}  // namespace radwalk
