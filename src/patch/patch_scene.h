#pragma once
// Patching a validated scene the one way every caller does (the radwalk commands' load_patches in
// apps/pipeline.cpp, the Python module's radwalk.load):
//   1. contacts: the objects standing on faces are found (contact.h, find_contacts), always, so that a caller can
//      report them; the supporting faces are cut along the footprints (cut_along_contacts) only when asked
//      (contact_cut) AND the faces are split (split.max_edge > 0 or split.max_area > 0, or splits_later: the
//      caller splits the patches itself, as --target-error does): kept input faces stay the patches, as the
//      CLI's --contact-cut (on by default) documents;
//   2. the per-face split (patching.h, make_patches) with split.max_edge and split.max_area;
//   3. the back sides (patch_set.h, add_back_sides): a back patch for every face of a two-sided material, or of
//      every material with two_sided, appended after all front patches.
// No output: what to print or record about the contacts and patches is the caller's (the counts are returned).
#include <cstddef>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "patch/contact.h"
#include "patch/contact_patches.h"
#include "patch/patch_set.h"
#include "patch/patching.h"

namespace radwalk {

struct ScenePatchingOptions {
  PatchingOptions split;     // --max-edge, --max-area (0, 0: the input faces are the patches)
  bool contact_cut = true;   // --contact-cut (default; --no-contact-cut): cut the supports along contacts when split
  bool splits_later = false; // the caller splits the patches afterwards (--target-error): cut as when splitting
  bool two_sided = false;    // --two-sided: every (non-dielectric) material two-sided
};

struct PatchedScene {
  Mesh mesh;                            // the validated mesh, its supporting faces cut when `cut`
  PatchSet patches;                     // front patches (face order), then the back patches
  std::vector<Contact> contacts;        // every contact found, cut or not (face indices of the mesh before the cut)
  std::vector<std::string> contact_lines;  // describe_contact of each, on the mesh before the cut
  std::vector<ContactRegion> contact_regions;  // contact_regions of them, on the mesh before the cut
  bool cut = false;                     // contact_cut and the faces are split (now or later)
  std::size_t contact_faces_cut = 0;    // faces replaced by their pieces
  std::size_t back_patches = 0;         // patches add_back_sides appended
  double contacts_seconds = 0;          // time of step 1 (for a run summary)
  double patch_seconds = 0;             // time of steps 2 and 3
};

// Steps 1 to 3 above on `mesh` (validated: mesh/validate.h). Throws InputError as make_patches does.
PatchedScene patch_scene(Mesh mesh, const ScenePatchingOptions& options);

}  // namespace radwalk
