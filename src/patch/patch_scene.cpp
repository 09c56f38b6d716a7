#include "patch/patch_scene.h"

#include <utility>

#include "core/timer.h"

namespace radwalk {

PatchedScene patch_scene(Mesh mesh, const ScenePatchingOptions& options) {
  PatchedScene scene;
  Timer timer;
  scene.contacts = find_contacts(mesh);
  for (const Contact& c : scene.contacts) scene.contact_lines.push_back(describe_contact(mesh, c));
  scene.contact_regions = contact_regions(mesh, scene.contacts);
  scene.cut = options.contact_cut && (options.split.max_edge > 0 || options.split.max_area > 0 || options.splits_later);
  if (scene.cut && !scene.contacts.empty())
    scene.mesh = cut_along_contacts(mesh, scene.contacts, &scene.contact_faces_cut);
  else
    scene.mesh = std::move(mesh);
  scene.contacts_seconds = timer.seconds();
  timer.reset();
  scene.patches = make_patches(scene.mesh, options.split);
  scene.back_patches = add_back_sides(scene.patches, options.two_sided);
  scene.patch_seconds = timer.seconds();
  return scene;
}

}  // namespace radwalk
