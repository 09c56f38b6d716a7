#pragma once
// The length unit of a scene, as `--unit` names the file's and `--scale` changes it (docs/units-and-formats.md,
// "Units"): coordinates are multiplied by the scale before anything else, so every length (areas, --max-edge,
// camera positions) is in the unit after scaling, and the radiosity B in W per that unit squared (Ke in W per
// sr and that unit squared).
//
// The unit after scaling, named in the summaries: with --unit U alone, U; with --unit U and --scale S, the unit
// of the table that S x (metres per U) lands on (mm, cm, m, in, ft; within a relative 1e-9: `--unit mm --scale
// 0.001` is metres), else "(1/S) U" ("0.5 mm" for --scale 2); without --unit, "mesh unit" (the file's own,
// unnamed), or "(1/S) mesh unit" with a scale.
#include <string>

#include "mesh/mesh.h"

namespace radwalk {

struct LengthUnit {
  std::string file_unit;  // mm, cm, m, in, ft, or "" (not given)
  double scale = 1;       // coordinates times this
  // The unit after scaling, as above; "m" and "mesh unit" for instance.
  std::string length() const;
  // The unit of B: "W/m^2", "W/(0.5 mm)^2", "W per mesh unit^2".
  std::string radiosity() const;
};

// Metres per unit of mm, cm, m, in, ft; 0 for another name.
double metres_per(const std::string& unit);
// "mm, cm, m, in, ft": the names metres_per knows.
const char* unit_names();

// Multiplies every vertex of the mesh by scale (finite, > 0: the caller checks).
void scale_mesh(Mesh& mesh, double scale);

}  // namespace radwalk
