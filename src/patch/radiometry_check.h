#pragma once
// The per-patch reflectance and emission a material could hold, for values set patch by patch (the Python
// module's writable Scene.rho and Scene.E) rather than read from a checked MTL.
#include "patch/patch_set.h"

namespace radwalk {

// Throws InputError naming the first patch, channel and value whose rho or E a material could not hold (the
// rules validate_mesh applies to Kd and Ke, mesh/validate.cpp): rho in [0, 1), E finite, >= 0 and at most
// pi kMaxKe (E = pi Ke).
void check_radiometry(const PatchSet& patches);

}  // namespace radwalk
