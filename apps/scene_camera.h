#pragma once
// The camera a scene is looked at from, shared by the path tracer's images and the ParaView state files:
// --camera if given (px py pz tx ty tz ux uy uz fov_deg); the Cornell box's own camera for a scene file named
// cornell_box*; otherwise a view of the bounding box from its -z side (40 degree vertical field of view) that
// frames the whole box.
#include <string>
#include <vector>

#include "pathtrace/camera.h"
#include "patch/patch_set.h"

namespace radwalk::app {

Camera scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& camera = {});

// A point the camera looks at: on its axis, level with the centre of the scene's bounding box.
Vec3 camera_focal_point(const Camera& camera, const PatchSet& patches);

}  // namespace radwalk::app
