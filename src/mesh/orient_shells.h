#pragma once
// Orientation of a scene's faces by shells (docs/units-and-formats.md, "Orientation"): faces that disagree with
// their neighbours are flipped, and closed shells are turned to face out of themselves, the enclosing room in.
//
// A shell is a set of faces joined through manifold edges (edges of exactly two faces, mesh/edge_table.h: welded
// vertices); a non-manifold edge (3+ faces) joins nothing, since it has no one "other side". Two faces agree
// across their shared edge when they run it in opposite directions (their normals are on the same side of the
// surface). A breadth-first walk from each shell's first face decides, face by face, whether it must be flipped
// to agree with the face it was reached from; a shell where some edge still disagrees after the walk is
// non-orientable (a Moebius strip, or faces folded through each other) and is reported, its walk kept.
// The shell's two consistent orientations are then the walk's and its reverse:
//   - consistent: the one that flips less area (the file's majority);
//   - outward: for a closed shell (every edge of its faces shared by exactly two of them) the one whose signed
//     volume V = 1/6 sum over the fan triangles (p0 - c) . ((p1 - c) x (p2 - c)) (c the shell's centroid; the
//     divergence theorem) is positive, so its normals point out of the enclosed volume, except for the room: the
//     closed shell that encloses the rest of the scene (its bounding box holds every other face's and a point of
//     another shell lies inside it, by the parity of a ray's crossings), or a closed shell that is the whole
//     scene, which is turned so that its faces point in (V < 0). An open shell takes the majority.
//   - none: nothing is flipped.
// Open shells (some edge of one face only), except those of emitting faces alone, are reported: the backs of
// their faces absorb the light that reaches them, so a thin or open part should be two-sided.
// A flip reverses the corner order (a b c d -> a d c b), keeping the first corner.
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace radwalk {

enum class OrientMode { none, consistent, outward };

// "none", "consistent", "outward".
const char* orient_mode_name(OrientMode mode);
// The mode of a name above; InputError naming the valid ones for another.
OrientMode parse_orient_mode(const std::string& name);

struct OpenShell {
  std::size_t first_face = 0;   // a face of the shell (the first in mesh order)
  std::size_t faces = 0;
  std::size_t boundary_edges = 0;
  double area = 0;
};

struct OrientationResult {
  std::size_t shells = 0, closed_shells = 0, rooms = 0, non_orientable = 0;
  // Closed shells that enclose the rest of the scene (the room's test above, in every mode; rooms counts those
  // turned in, by outward only).
  std::size_t enclosing_shells = 0;
  std::size_t flipped_faces = 0;
  double flipped_area = 0;
  std::vector<std::size_t> flipped;           // the faces flipped (mesh order)
  std::vector<OpenShell> open_shells;         // open shells not made of emitters alone
  std::vector<std::size_t> open_shell_faces;  // every face of those shells (mesh order)
  std::vector<std::size_t> non_orientable_faces;  // a face of each non-orientable shell
};

// Orients mesh's faces as above (faces flipped in place). Precondition: every face index in range and every face
// with area (validate_mesh runs it after its repairs).
OrientationResult orient_shells(Mesh& mesh, OrientMode mode);

}  // namespace radwalk
