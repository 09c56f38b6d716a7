#include "apps/discretisation_error.h"

#include <cmath>

#include "apps/run_metadata.h"
#include "apps/statistical_error.h"
#include "core/timer.h"
#include "patch/patch_grouping.h"
#include "solve/discretisation_error.h"
#include "solve/group_mean_error.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

std::string add_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem, Solution& solution,
                                     RunSummary& summary, int directions, std::uint64_t seed,
                                     const GroupNoiseModel& noise) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  if (solution.B.rows() != N || directions <= 0) return {};
  const EmbreeVisibility visibility(patches);
  const DiscretisationError error = discretisation_error(patches, visibility, problem, solution.B, directions, seed);
  solution.B_disc = error.standard_error;
  return report_discretisation_error(patches, problem, error, solution, summary, noise);
}

std::string report_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem,
                                        const DiscretisationError& error, const Solution& solution,
                                        RunSummary& summary, const GroupNoiseModel& noise, bool materials) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  const double disc = relative_error(patches, solution.B, solution.B_disc);
  const double stat = solution.B_se.rows() == N ? relative_error(patches, solution.B, solution.B_se) : 0.0;
  const double total = relative_error(patches, solution.B, total_error(solution.B_se, solution.B_disc));
  auto& j = summary.json()["error_estimate"];
  j["discretisation"] = {
      {"relative", disc},
      {"points_per_patch", error.points},
      {"near_field_patches", error.near_field_patches},
      {"directions_per_point", error.directions},
      {"rays", error.rays},
      {"sweeps", error.sweeps},
      {"form_factors", error.own_form_factors ? "the estimate's own rays" : "the solved F"},
      {"method", "the within-patch fluctuation of a one-bounce gather, shot with common random numbers: e = (I - H)^-1 d, "
                 "B_disc the root mean square of e given its estimate, with a prior fitted over the patches "
                 "(docs/theory/discretisation_error.md)"}};
  j["total"] = {{"relative", total}, {"combination", "B_err = sqrt(B_se^2 + B_disc^2)"}};
  summary.add_timing("discretisation_error", error.seconds);
  std::string line = "estimated error e = " + percent(total) + " (statistical " + percent(stat) + ", discretisation " +
                     percent(disc) + "; 1 standard deviation, relative to B over the reflecting patches)";
  // Each material's mean (solve/group_mean_error.h): its patches' errors are correlated, so a mean can be off by
  // more than e. Needs every row of the solved F (not over MPI's row blocks, not the estimate's own rays).
  if (materials && problem.row_blocks.empty() && problem.F.nonZeros() > 0 && !error.own_form_factors) {
    const std::string means =
        report_material_means(group_mean_errors(patches, group_patches(patches, "material"), problem, solution.B,
                                                solution.B_se, error.source, error.source_sd, HUGE_VAL, noise),
                              summary);
    if (!means.empty()) line += "\n" + means;
  }
  return line;
}

std::string report_material_means(const std::vector<GroupMeanError>& means, RunSummary& summary) {
  summary.json()["error_estimate"]["materials"] = group_mean_errors_json(means);
  const GroupMeanError* worst = nullptr;
  for (const GroupMeanError& g : means)
    if (g.counted && (!worst || g.total > worst->total)) worst = &g;
  if (!worst) return {};
  return "estimated error of a material's mean: at most " + percent(worst->total) + " (" + worst->name +
         ": discretisation " + percent(worst->discretisation) + ", statistical " + percent(worst->statistical) +
         (worst->statistical_kind == "bound" ? " (a bound)" : "") +
         "; each material's in the JSON's error_estimate.materials)";
}

}  // namespace radwalk::app
