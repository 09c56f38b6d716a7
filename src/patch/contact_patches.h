#pragma once
// The patches in contact with another surface (contact.h): the part of a support face under a footprint (the floor
// under a block) and the faces lying on the support back to back (the block's bottom). Both radiate only into the
// backs of faces (the floor under a bottom, the bottom's own inside): in reality they exchange heat by conduction,
// not radiation, so `radwalk exchange --contact-faces exclude` leaves them out.
//
// A contact region is what of a contact decides which patches touch: the support's unit normal n, the footprint K
// (convex, counter-clockwise about n), the outlines of the support faces K overlaps and their input faces. Regions
// are taken on the mesh before the contact cut, so they do not depend on whether the faces were cut.
//
// Patch i is a contact patch of a region iff its centroid x lies in the support's plane (|(x - K_0) . n| <= tol),
// strictly inside K, and
//   - its normal is opposite (n_i . n < -0.999) and x lies inside one of the support faces' outlines (a face lying
//     on the support, back to back: a bottom; only the part of it over the support touches it: a large face found
//     lying on a small one, the floor on a block's bottom, touches it only there), or
//   - its normal is along n (n_i . n > 0.999), its input face is one of the support faces and x lies inside one of
//     the region's bottom patches (the support's own part under a bottom). Under an object without a bottom (open
//     below: a cabinet whose inside sees the floor) the support is not in contact with anything and radiates as any
//     face: its part under the footprint belongs to the object's inside.
// Only the centroid decides: a patch across K's outline counts whole on the side of its centroid, which is why
// `exchange --contact-faces exclude` cuts the supports along the footprints first (patch_scene.h).
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "mesh/mesh.h"
#include "patch/contact.h"
#include "patch/patch_set.h"

namespace radwalk {

struct ContactRegion {
  Vec3 normal = Vec3::Zero();                 // the support's unit normal
  std::vector<Vec3> footprint;                // K
  std::vector<std::vector<Vec3>> supports;    // outlines of the support faces K overlaps
  std::vector<long> support_faces;            // their input faces (Mesh::source_face)
};

// The regions of the convex contacts with a footprint of at least three corners, on the mesh the contacts were
// found on (before any cut).
std::vector<ContactRegion> contact_regions(const Mesh& mesh, const std::vector<Contact>& contacts);

// in_contact[i] for every patch, by the rule above, with tol = kContactTolerance x the patches' scene extent. The
// patches a region tests are those whose centroid lies near its footprint's bounding box, found through a grid of
// the centroids: O(N + sum over the regions of the patches near each footprint), not O(regions x N).
std::vector<bool> contact_patches(const std::vector<ContactRegion>& regions, const PatchSet& patches);

}  // namespace radwalk
