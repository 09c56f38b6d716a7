#pragma once
// A ParaView Python state file (.py) that opens a radwalk .vtp as a figure, in one step: coloured by the
// one-component radiosity B (vtp_writer.h: the channel mean, W per square length unit) with a perceptual colour
// map (Viridis), over a range that leaves the emitters out (StateColouring: the min..max of B over the
// non-emitting patches, computed when writing), a colour bar titled with the field's name and unit, smooth
// shading (the point field B, Gouraud interpolation, when the file has it; else the cell field), unlit (the
// colour is the value itself), black background (UseColorPaletteForBackground = 0), and the given camera
// (apps/scene_camera.h: the one camera rule), set after the first render (ParaView resets the camera on it). A
// file without the field is shown with ParaView's defaults, from the same camera.
// Load it with File > Load State (Python state file), `paraview --state=FILE.py`, or `pvpython FILE.py`.
// The data file is looked up next to the state file first (by its name), then at the path given here, so the two
// can be moved together. Written atomically.
#include <string>
#include <vector>

#include "core/types.h"
#include "patch/patch_set.h"

namespace radwalk {

struct ViewPoint {
  Vec3 position = Vec3(0, 0, -1);
  Vec3 focal_point = Vec3(0, 0, 0);
  Vec3 up = Vec3(0, 1, 0);
  double view_angle_deg = 30;  // vertical field of view
};

struct StateColouring {
  std::string field;  // the one-component array to colour by ("B"); empty: ParaView's defaults
  std::string title;  // the colour bar's title: the field's name and unit
  double lo = 0, hi = 1;  // the colour map's range, lo < hi
  std::string preset = "Viridis (matplotlib)";  // ParaView's colour map preset
  std::string range_rule = "range without the emitters";  // how lo..hi were chosen, for the file's comment
};

// The colouring of the radiosity: B's channel mean over the patches that emit nothing (E = 0 in every channel;
// over all patches when every patch emits), titled "B [W/unit^2]" (unit: the scene's length unit). B_rgb holds
// N x 3 values, patch-major. A range of one value is widened to lo < hi.
StateColouring radiosity_colouring(const PatchSet& patches, const std::vector<double>& B_rgb);

// The colouring of a heat exchange (`radwalk exchange`): the net heat flux q (one component, W/m^2 leaving) with
// the diverging preset "Cool to Warm" (blue: heat gained, red: heat lost) over a range symmetric about 0,
// [-max |q|, max |q|] over the finite values, titled "q [W/m^2] (net leaving)"; 0..1 widened when q is 0 everywhere.
StateColouring heat_flux_colouring(const std::vector<double>& q);

// run_id: when not empty, the comment line "# run_id RUN_ID" (the run of the .vtp, apps/run_metadata.h).
void write_paraview_state(const std::string& path, const std::string& vtp, const ViewPoint& view,
                          const StateColouring& colouring = {}, const std::string& run_id = "");

}  // namespace radwalk
