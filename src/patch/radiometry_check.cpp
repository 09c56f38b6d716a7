#include "patch/radiometry_check.h"

#include <string>

#include "core/error.h"
#include "mesh/validate.h"

namespace radwalk {

void check_radiometry(const PatchSet& patches) {
  const double max_E = kPi * kMaxKe;
  for (std::size_t i = 0; i < patches.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const auto at = [&] { return "patch " + std::to_string(i) + ", channel " + std::to_string(c) + ": "; };
      const double rho = patches.rho[i][c], E = patches.E[i][c];
      if (!(rho >= 0 && rho < 1))
        throw InputError(at() + "rho = " + number_text(rho) +
                         " is outside [0, 1), the range of a material's Kd (the radiosity equation needs rho < 1)");
      if (!(E >= 0 && E <= max_E))
        throw InputError(at() + "E = " + number_text(E) + " must be finite, >= 0 and at most pi x " +
                         number_text(kMaxKe) + " (E = pi Ke, the bound on a material's Ke)");
    }
}

}  // namespace radwalk
