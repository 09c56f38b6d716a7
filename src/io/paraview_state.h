#pragma once
// A ParaView Python state file (.py) that opens a radwalk .vtp ready to look at: coloured by the display array
// B_srgb with "Map Scalars" off (true colours), no lighting (the colour is the patch's own radiance), black
// background (UseColorPaletteForBackground = 0), and the given camera, set after the first render (ParaView resets
// the camera on it). A file without B_srgb is shown with ParaView's defaults, from the same camera.
// Load it with File > Load State (Python state file), `paraview --state=FILE.py`, or `pvpython FILE.py`.
// The data file is looked up next to the state file first (by its name), then at the path given here, so the two
// can be moved together. Written atomically.
#include <string>

#include "core/types.h"

namespace radwalk {

struct ViewPoint {
  Vec3 position = Vec3(0, 0, -1);
  Vec3 focal_point = Vec3(0, 0, 0);
  Vec3 up = Vec3(0, 1, 0);
  double view_angle_deg = 30;  // vertical field of view
};

// run_id: when not empty, the comment line "# run_id RUN_ID" (the run of the .vtp, apps/run_metadata.h).
void write_paraview_state(const std::string& path, const std::string& vtp, const ViewPoint& view,
                          const std::string& run_id = "");

}  // namespace radwalk
