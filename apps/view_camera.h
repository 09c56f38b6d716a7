#pragma once
// The one camera rule of radwalk's views of a .vtp: the ParaView state (--paraview-state), and the same rule in
// scripts/camera_rule.py for scripts/paraview_render.py and scripts/render_vtp.py (tests/paraview checks that the
// two agree on bundled scenes). In order:
//   - a scene file named cornell_box*: the Cornell box's own camera (position (278, 273, -800), looking along +z
//     at (278, 273, 0), up +y, vertical field of view 2 atan(0.0125 / 0.035) = 39.31 degrees);
//   - a closed scene, i.e. every one of kViewProbes directions (a Fibonacci sphere about +y, the first hit from
//     the bounding box's centre c) hits the front of a patch: inside, standing on the axis through c at 5 % of the
//     box's depth from its front (-z) side, looking along +z at c, up +y, 60 degrees;
//   - otherwise outside: looking along +z at c from the -z side, at the distance r / tan(20 degrees) + dz / 2
//     from c (r: half the box's diagonal, dz: its depth), up +y, 40 degrees (the whole bounding sphere in view).
// No random numbers: the same scene gives the same camera.
#include <string>

#include "io/paraview_state.h"
#include "patch/patch_set.h"

namespace radwalk::app {

inline constexpr int kViewProbes = 64;

// Direction k of the kViewProbes probe directions (scripts/camera_rule.py: probe_direction).
Vec3 view_probe_direction(int k);

ViewPoint view_camera(const std::string& scene, const PatchSet& patches);

}  // namespace radwalk::app
