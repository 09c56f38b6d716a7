#include "apps/discretisation_error.h"

#include <utility>

#include "apps/statistical_error.h"
#include "core/timer.h"
#include "solve/discretisation_error.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

std::string add_discretisation_error(const PatchSet& patches, const RadiosityProblem& problem, Solution& solution,
                                     RunSummary& summary, int directions, std::uint64_t seed,
                                     std::vector<double>* shooter_share) {
  const Eigen::Index N = static_cast<Eigen::Index>(patches.size());
  if (solution.B.rows() != N || directions <= 0) return {};
  const EmbreeVisibility visibility(patches);
  ShooterAttribution attribution;
  const DiscretisationError error = discretisation_error(patches, visibility, problem, solution.B, directions, seed,
                                                        shooter_share ? &attribution : nullptr);
  if (shooter_share) *shooter_share = std::move(attribution.share);
  solution.B_disc = error.standard_error;
  const double disc = relative_error(patches, solution.B, solution.B_disc);
  const double stat = solution.B_se.rows() == N ? relative_error(patches, solution.B, solution.B_se) : 0.0;
  const double total = relative_error(patches, solution.B, total_error(solution.B_se, solution.B_disc));
  auto& j = summary.json()["error_estimate"];
  j["discretisation"] = {
      {"relative", disc},
      {"points_per_patch", error.points},
      {"directions_per_point", error.directions},
      {"rays", error.rays},
      {"sweeps", error.sweeps},
      {"form_factors", error.own_form_factors ? "the estimate's own rays" : "the solved F"},
      {"method", "the within-patch fluctuation of a one-bounce gather, shot with common random numbers: e = (I - H)^-1 d, "
                 "B_disc = sqrt(e^2 + Var(e)) (docs/theory/discretisation_error.md)"}};
  j["total"] = {{"relative", total}, {"combination", "B_err = sqrt(B_se^2 + B_disc^2)"}};
  summary.add_timing("discretisation_error", error.seconds);
  return "estimated error e = " + percent(total) + " (statistical " + percent(stat) + ", discretisation " +
         percent(disc) + "; 1 standard deviation, relative to B over the reflecting patches)";
}

}  // namespace radwalk::app
