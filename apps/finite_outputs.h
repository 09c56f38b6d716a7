#pragma once
// Outputs never hold a number that overflowed: a result that does not fit a double is refused before anything is
// written, in one line naming the quantity, the patch (or pixel) and channel, and what to do (NumericalError,
// exit 3), instead of an empty CSV cell, a JSON null or "inf" on stdout. Each command checks what it computed
// before writing it (pathtrace: the image before the image file, the patch averages before their files).
//
// The estimators scale before squaring (core/moments.h), so what reaches these checks infinite is a quantity whose
// own value is above 1.8e308: with an emission near the largest legal (Ke = 1e300), the per-walk (per-sample)
// variance var ~ B^2 of the Monte Carlo methods. NaN is not checked: it marks what a run did not compute (patches a
// gathering run did not estimate, a variance's error from one run) and the writers leave it empty by design.
#include <string>
#include <vector>

#include "core/image.h"
#include "core/solution.h"
#include "patch/patch_set.h"
#include "walk/walk_compare.h"

namespace radwalk::app {

// B, B_se and var of a solver, walk or path tracer: NumericalError naming `command`, the first infinite entry and
// max E when one of them is +-inf.
void refuse_overflow(const Solution& solution, const std::string& command, double max_E);

// The rows of compare: mean, var and var_se (var_theory is infinite by design when the second moment diverges;
// z and efficiency are infinite by design for a zero-variance method).
void refuse_overflow(const std::vector<CompareRow>& rows, double max_E);

// An image's mean and standard error, to be written to `file`: not finite, or for an .exr (32-bit floats) above
// the largest float (3.4e38), which the file would hold as infinity.
void refuse_overflow(const RgbImage& mean, const RgbImage& se, const std::string& file, double max_E);

}  // namespace radwalk::app
