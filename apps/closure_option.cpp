#include "apps/closure_option.h"

#include <string>

#include "apps/pipeline.h"
#include "core/error.h"
#include "core/format_number.h"
#include "formfactor/closure.h"

namespace radwalk::app {
void apply_closure(FormFactors& ff, const PatchSet& patches, RunSummary& summary, const std::string& source) {
  const std::size_t n = patches.size();
  const bool traced = ff.rays.size() == n && n > 0;
  std::uint64_t rays = 0, leaked = 0;
  if (traced) {
    std::size_t worst = 0;
    double worst_fraction = -1;
    for (std::size_t i = 0; i < n; ++i) {
      rays += ff.rays[i];
      leaked += std::uint64_t(ff.escaped[i]) + ff.back_hits[i];
      const double f = double(ff.escaped[i] + ff.back_hits[i]) / double(std::max<std::uint32_t>(ff.rays[i], 1));
      if (f > worst_fraction) worst_fraction = f, worst = i;
    }
    if (double(leaked) > kClosureLeakTolerance * double(rays))
      throw InputError(
          "--enforce-closure needs a closed scene, but " + std::to_string(leaked) + " of " +
          std::to_string(rays) + " rays (" + format_number(100.0 * double(leaked) / double(rays), 3) +
          " %, more than " + format_number(100 * kClosureLeakTolerance, 3) +
          " %) escaped or hit the back of a "
          "face, most from patch " +
          std::to_string(worst) + " (input face " + std::to_string(patches.face[worst]) + ", object '" +
          patches.object_of(worst) + "', " + format_number(100 * worst_fraction, 3) +
          " % of its rays): closing the rows would send that radiation "
          "back into the scene. Close the scene (or make its faces two-sided / oriented inward), or "
          "drop --enforce-closure (the escaping part then reaches the ambient)");
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const double row = double(ff.F.row(Eigen::Index(i)).sum());
      if (row < 1 - kClosureLeakTolerance)
        throw InputError("--enforce-closure needs a closed scene, but row " + std::to_string(i) + " of " +
                         source + " (input face " + std::to_string(patches.face[i]) + ", object '" +
                         patches.object_of(i) + "') sums to " + format_number(row) + " < 1 - " +
                         format_number(kClosureLeakTolerance, 3) +
                         ": part of its radiation leaves the scene; drop --enforce-closure");
    }
  }
  const ClosureChange c = enforce_closure(ff.F, patches.area, ff.rays);
  ff.closure_max_change = c.row_max_change;
  ff.closure_rms_change = c.row_rms_change;
  if (traced) {
    std::fill(ff.escaped.begin(), ff.escaped.end(), 0u);
    std::fill(ff.back_hits.begin(), ff.back_hits.end(), 0u);
  }
  auto& j = summary.json()["closure"];
  j["method"] = "least-squares adjustment of the exchange areas, variance-weighted, symmetric, rows summing to 1, "
                "non-negative (docs/theory/closure.md)";
  j["rays_leaked_total"] = leaked;
  j["rays_total"] = rays;
  j["max_change"] = c.max_change;
  j["rms_change"] = c.rms_change;
  j["max_row_defect_before"] = c.max_row_defect_before;
  j["max_row_defect_after"] = c.max_row_defect_after;
  j["max_reciprocity_defect_after"] = c.max_reciprocity_defect_after;
  j["clipped_to_zero"] = c.clipped;
  j["active_set_rounds"] = c.rounds;
  j["cg_iterations"] = c.cg_iterations;
  j["cg_relative_residual"] = c.cg_error;
  note("closure enforced: F changed by at most " + format_number(c.max_change, 3) + " (RMS " +
       format_number(c.rms_change, 3) + ") per entry; row sums were within " +
       format_number(c.max_row_defect_before, 3) + " of 1, now " + format_number(c.max_row_defect_after, 3) +
       " (float rounding); reciprocity defect now " + format_number(c.max_reciprocity_defect_after, 3) +
       (c.clipped > 0 ? "; " + std::to_string(c.clipped) + " entries clipped to 0" : std::string()) +
       " (per patch: closure_max_change, closure_rms_change)");
}

}  // namespace radwalk::app
