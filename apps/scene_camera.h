#pragma once
// The one camera rule: the camera a scene is looked at from, shared by the path tracer's images (pathtrace
// --image, measure --response camera), the ParaView state files (--paraview-state) and, mirrored in Python by
// scripts/camera_rule.py, scripts/render_vtp.py and scripts/paraview_render.py (tests/python/test_camera_rule.py
// checks that the two agree):
//   - --camera if given (px py pz tx ty tz ux uy uz fov_deg): source "option";
//   - the Cornell box's own camera for a scene file named cornell_box*: source "cornell_box";
//   - a closed scene (a point inside it from which every probe ray hits the front of a patch: the bounding box's
//     centre, else one of the six points a quarter of the box's size away from it along an axis): when the scene
//     has objects (non-emitting patches off the bounding box's six planes, i.e. not the room's own floor, walls
//     or ceiling) the camera looks at their area-weighted centroid with a 60 degree vertical field of view, from
//     the point (0.8 of the way from that enclosed point to a probe hit) that sees the most of them (sampled
//     object patches whose centroid is in the image and whose front is seen unoccluded), source "inside";
//     without objects it stands at the enclosed point, 60 degree vertical field of view, and looks at the
//     largest lit region: of the probe
//     directions (a fixed Fibonacci sphere of kProbeRays directions), the one whose field-of-view cone holds the
//     most directly lit surface (per probe hit, the unoccluded irradiance sum_j E_j A_j cos cos / (pi r^2) from
//     the emitting patches' centroids, times the solid angle per probe), source "inside"; with no emitter it
//     looks along the longest probe ray;
//   - otherwise a view from outside that frames the bounding box's sphere (40 degree vertical field of view),
//     along the direction (+z first, then the other axes and the diagonals) whose 24 x 24 pixel-centre rays hit
//     the most fronts of patches, emitters counted twice (a tie keeps the earlier): source "outside".
// Up is +y unless the view direction is within about 8 degrees of it (then +z). No random numbers: the probes are
// a fixed set.
#include <string>
#include <vector>

#include "io/paraview_state.h"
#include "pathtrace/camera.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk::app {

inline constexpr int kProbeRays = 512;

struct SceneCamera {
  Camera camera;
  std::string source;  // option, cornell_box, inside, outside
};

// visibility: the patches' scene if the caller has one (else one is built when needed).
SceneCamera fit_scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& camera = {},
                             const Visibility* visibility = nullptr);
Camera scene_camera(const std::string& scene, const PatchSet& patches, const std::vector<double>& camera = {});

// A point the camera looks at: on its axis, level with the centre of the scene's bounding box, at least a quarter
// of the box's diagonal in front of the camera.
Vec3 camera_focal_point(const Camera& camera, const PatchSet& patches);

// The camera as ParaView's view takes it: position, focal point (camera_focal_point), up made orthogonal to the
// view direction (up - (up . d) d, normalised: the image's up, as PinholeCamera makes it) and vertical field of
// view in degrees.
ViewPoint view_point(const Camera& camera, const PatchSet& patches);

}  // namespace radwalk::app
