// Sliver patches: a thin receiver gets few of the rays shot at it, so its column of F is noisy and reciprocity
// A_i F_ij = A_j F_ji fails by much more than for a square; the diagnostics must show it and
// enforce_reciprocity (--reciprocity) must repair it.
#include <catch2/catch.hpp>
#include <cmath>

#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factors.h"
#include "formfactor/reciprocity.h"
#include "patch/patch_builder.h"
#include "visibility/brute_force_visibility.h"

using namespace radwalk;

namespace {

// Unit square at z = 0 facing +z, and a receiver at z = 1 facing -z: x in [0, 1], y in [0.5 - w/2, 0.5 + w/2].
PatchSet pair(double w) {
  PatchBuilder b;
  const int m = b.add_material("white", Rgb::Constant(0.5));
  b.add_quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), m);
  const double y0 = 0.5 - w / 2, y1 = 0.5 + w / 2;
  b.add_quad(Vec3(0, y0, 1), Vec3(0, y1, 1), Vec3(1, y1, 1), Vec3(1, y0, 1), m);
  return b.build();
}

struct PairStats {
  double rms_reciprocity = 0;  // RMS over seeds of the relative reciprocity error of the pair
  double max_change = 0;       // largest relative change enforce_reciprocity made
  double max_after = 0;        // largest reciprocity error left after enforcing
};

PairStats measure(double w, int seeds, long rays) {
  const PatchSet patches = pair(w);
  const BruteForceVisibility visibility(patches);
  PairStats st;
  double sum2 = 0;
  for (int s = 1; s <= seeds; ++s) {
    FormFactorOptions o;
    o.rays_per_patch = rays;
    o.seed = std::uint64_t(s);
    FormFactors ff = estimate_form_factors(patches, visibility, o);
    const FormFactorDiagnostics d = diagnose_form_factors(ff.F, patches.area, ff.rays, ff.back_hits);
    sum2 += d.reciprocity_error[0] * d.reciprocity_error[0];
    const ReciprocityChange c = enforce_reciprocity(ff.F, patches.area);
    st.max_change = std::max(st.max_change, c.max_relative_change);
    const FormFactorDiagnostics after = diagnose_form_factors(ff.F, patches.area);
    st.max_after = std::max({st.max_after, after.reciprocity_error[0], after.reciprocity_error[1]});
  }
  st.rms_reciprocity = std::sqrt(sum2 / seeds);
  return st;
}

}  // namespace

TEST_CASE("sliver receiver: reciprocity error is reported many times larger, and --reciprocity repairs it",
          "[failure][formfactor]") {
  // 20000 rays per patch. Square: F = 0.1998 is hit ~4000 times from either side (relative error ~1 %, less with
  // stratification). Sliver w = 0.005: about 0.0013 of the square's rays (~25 hits) reach it, a relative
  // error of ~20 %, while its own row is well resolved. RMS over 20 seeds makes the comparison robust.
  const PairStats square = measure(1.0, 20, 20000);
  const PairStats sliver = measure(0.005, 20, 20000);
  INFO("RMS reciprocity error: square " << square.rms_reciprocity << ", sliver " << sliver.rms_reciprocity);
  CHECK(square.rms_reciprocity < 0.03);
  CHECK(sliver.rms_reciprocity > 0.05);
  CHECK(sliver.rms_reciprocity > 3 * square.rms_reciprocity);
  // Enforcing reciprocity averages each pair: the change it reports is of the size of the error, and none is left
  // (no row of this open pair exceeds 1 after averaging, so nothing is rescaled).
  CHECK(sliver.max_change > 0.05);
  CHECK(sliver.max_after < 1e-6);
  CHECK(square.max_after < 1e-6);
}
