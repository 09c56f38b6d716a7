#pragma once
// Writes patches as OBJ + MTL so that they load back as the same scene: one material per input material
// (Kd = rho, Ke = E / pi, plus the non-diffuse parameters), faces in patch order (patch i = face i of the output).
// The MTL file is PATH with its extension replaced by .mtl. Both files are written atomically.
#include <string>

#include "patch/patch_set.h"

namespace radwalk {

void write_obj(const std::string& path, const PatchSet& patches);

}  // namespace radwalk
