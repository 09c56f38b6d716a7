#pragma once
// Contacts: objects standing on a face (a block on a floor), and the cut of the supporting face along the contact
// footprint, so that no patch averages a lit part of the floor with the part hidden under the object.
//
// Detection (find_contacts), on a validated Mesh, with tol = kContactTolerance x the scene's extent:
//   - support surfaces: faces joined through shared edges when coplanar (normals within 1e-6 rad, each one's
//     corners within tol of the other's plane) and facing the same way, e.g. a floor cut into a grid;
//   - contact edges of a surface: mesh edges that are not edges of the surface itself, both of whose end points lie
//     within tol of its plane and inside its bounding box, and that are a side of a face F rising from the
//     surface's front: F not coplanar with it and every corner of F at signed distance >= -tol (above the floor);
//   - footprints: the contact edges, joined at welded vertices, that form a closed loop (every vertex on two of
//     them). The loop is the footprint polygon K. It is kept when the rising faces face away from K's inside (a
//     solid standing on the floor; walls standing around a floor face into it and are not a contact) and K is
//     convex (a non-convex footprint is reported, not cut);
//   - a face G lying on the surface back to back (coplanar, normal opposite: a block's bottom) whose corners are not
//     already a footprint loop's is a footprint too (K = G).
//   - contact lines: the contact edges that belong to no closed loop (a board's edge touching a shelf's side
//     panel, a thin sheet standing on the floor). Each lists the surface's faces whose interior it crosses (the
//     segment's part inside the face is longer than tol and leaves area on both sides). A face is cut along at most
//     kMaxContactLinesPerFace of them; the others are reported, not cut (convex = false).
// Each footprint lists the surface's faces it overlaps (area of S n K above 1e-9 of S's area).
//
// Cutting (cut_along_contacts): every overlapped support face S (convex: a triangle or convex quad) is replaced in
// place by S n K and the pieces of S \ K, the arms of a pinwheel about K: arm k is the part of S outside the line of
// K's edge k and inside the line of its neighbouring edge (the previous one, or the next one for the pinwheel
// turning the other way), so each footprint edge's line is continued beyond one of its corners only, up to S's
// boundary (a cut along whole chords, both ways across S, left wedges and slivers where the lines crossed S's other
// pieces). Of the two pinwheels, the one whose pieces have the larger smallest angle. Each piece is a convex
// polygon, given as quads and triangles: a fan of quads (one triangle if the corner count is odd) from the corner
// whose fan has the largest smallest angle. Several footprints on one face cut the pieces in turn (a piece already
// under a footprint is not cut again). Pieces keep S's orientation, material, group,
// line and input face (Mesh::face_source), so the `face` field still names the input face; they tile S (areas add
// up to rounding). A cut point on an edge is computed from the edge's end points in a fixed order, so two faces
// sharing the edge get the same point. Then every piece a contact line crosses is cut in two along the line (the whole
// chord of the piece, so pieces stay convex: a panel touched by a shelf board's edge is cut into the compartments on
// either side). Pieces are made before the --max-edge split, which then splits each piece on its own.
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/mesh.h"

namespace radwalk {

inline constexpr double kContactTolerance = 1e-6;  // of the scene's extent
inline constexpr int kMaxContactLinesPerFace = 16;

struct Contact {
  std::vector<Vec3> footprint;           // convex polygon K, counter-clockwise about the support's normal; a
                                         // contact line: its two end points
  double area = 0;                       // of K (0 for a line)
  std::vector<std::int32_t> standing;    // faces whose sides are K's edges (or the face lying on the support)
  std::vector<std::int32_t> supports;    // faces of the support surface that K overlaps
  bool convex = true;                    // false: reported, not cut (a non-convex footprint, a line beyond the limit)
  bool lying = false;                    // K is a face lying on the support back to back
  bool line = false;                     // an edge touching the support along a segment (no footprint)
};

std::vector<Contact> find_contacts(const Mesh& mesh);

// The mesh with every support face of a convex contact replaced by its pieces (see above). cut_faces, if given,
// gets the number of faces that were cut.
Mesh cut_along_contacts(const Mesh& mesh, const std::vector<Contact>& contacts, std::size_t* cut_faces = nullptr);

// One line for a contact: what stands on what (faces with their object, group and material), the footprint's
// corners count and area.
std::string describe_contact(const Mesh& mesh, const Contact& contact);

}  // namespace radwalk
