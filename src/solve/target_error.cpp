#include "solve/target_error.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/check.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/timer.h"
#include "patch/refine.h"
#include "solve/discretisation_error.h"
#include "solve/problem.h"
#include "solve/refinement_marks.h"

namespace radwalk {
namespace {

constexpr long kMaxRaysPerPatch = 1L << 24;

bool counted(const PatchSet& patches, std::size_t i) {
  return patches.E[i].maxCoeff() <= 0 && patches.rho[i].maxCoeff() > 0;
}

// The contributions c_i = A_i sum_c B_disc_ic^2 of the counted patches (0 for the others), scaled by 1 / s^2
// (s = moment_scale of B_disc: values near the largest double).
std::vector<double> contributions(const PatchSet& patches, const PatchRgb& B_disc, double s) {
  std::vector<double> c(patches.size(), 0.0);
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (counted(patches, i)) c[i] = patches.area[i] * (B_disc.row(static_cast<Eigen::Index>(i)) / s).square().sum();
  return c;
}

// The patches to split: the largest contributions c_i of the counted patches until their sum reaches `fraction`
// of the total, and the largest shooter shares (when given) until theirs do (solve/refinement_marks.h), at most
// `room` of them (ties: lower index first).
std::vector<bool> patches_to_split(const PatchSet& patches, const PatchRgb& B_disc, const std::vector<double>& shooter,
                                   double fraction, std::size_t room) {
  const double s = moment_scale(B_disc.size() > 0 ? B_disc.abs().maxCoeff() : 0.0);
  const std::vector<double> c = contributions(patches, B_disc, s);
  std::vector<double> shot(shooter.size());
  for (std::size_t i = 0; i < shooter.size(); ++i) shot[i] = shooter[i] / (s * s);
  return refinement_marks(c, shot, fraction, 0.0, room);
}

// The starting patches of TargetErrorOptions::start_patches: rounds of splitting every patch above twice the mean
// area, each round only if the result stays within max_patches (its 3 new patches per split counted).
PatchSet split_to_start(PatchSet patches, const TargetErrorOptions& options) {
  const double largest = 2 * patches.total_area() / double(options.start_patches);
  for (;;) {
    std::vector<bool> split(patches.size(), false);
    std::size_t marked = 0;
    for (std::size_t i = 0; i < patches.size(); ++i)
      if (patches.area[i] > largest) split[i] = true, ++marked;
    if (marked == 0 || patches.size() + 3 * marked > options.max_patches) return patches;
    patches = split_patches(patches, split);
  }
}


}  // namespace

double relative_error(const PatchSet& patches, const PatchRgb& B, const PatchRgb& d) {
  const double s = moment_scale(B.size() > 0 ? B.abs().maxCoeff() : 0.0);
  double error = 0, size = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (!counted(patches, i)) continue;
    const auto row = static_cast<Eigen::Index>(i);
    error += patches.area[i] * (d.row(row) / s).square().sum();
    size += patches.area[i] * (B.row(row) / s).square().sum();
  }
  return size > 0 ? std::sqrt(error / size) : 0.0;
}

TargetErrorPlan plan_target_error_step(double statistical, double discretisation, double E, long rays) {
  TargetErrorPlan plan;
  plan.refine = discretisation > kRefineAbove * E;
  const double t_d = plan.refine ? kPlanTarget * E : discretisation;
  const double t_s = plan.refine ? kPlanTarget * E : std::sqrt(E * E - discretisation * discretisation);
  plan.next_rays = rays;
  if (statistical > t_s) {
    const double factor = std::max(1.25, 1.1 * (statistical / t_s) * (statistical / t_s));
    plan.next_rays = static_cast<long>(std::ceil(std::min(double(kMaxRaysPerPatch), double(rays) * factor)));
  }
  if (plan.refine) plan.split_fraction = std::min(1.0, 2 * (1 - t_d * t_d / (discretisation * discretisation)));
  return plan;
}

std::vector<GroupMeanError> step_group_errors(const PatchSet& patches, const TargetErrorStage& stage, const PatchRgb& B,
                                              const PatchRgb& B_se, const std::string& each, double E,
                                              TargetErrorStep& record) {
  if (each.empty()) return {};
  if (stage.source.rows() != B.rows() || stage.source_sd.rows() != B.rows())
    throw InputError("the target error per " + each + " needs the discretisation estimate's source, which this "
                     "step did not give");
  const std::shared_ptr<const RadiosityProblem> problem =
      stage.problem ? stage.problem
                    : std::make_shared<const RadiosityProblem>(make_problem(patches, SparseF(stage.form_factors.F)));
  const double E_g = group_target(E);
  // The shares of every group that plan_group_targets may split for: above E_g, or near it (disc_g > 0.8 E_g).
  std::vector<GroupMeanError> groups = group_mean_errors(patches, group_patches(patches, each), *problem, B, B_se,
                                                         stage.source, stage.source_sd, kRefineAbove * E_g, stage.noise);
  for (const GroupMeanError& g : groups) {
    if (!g.counted) continue;
    ++record.groups;
    if (g.total <= E_g) ++record.groups_within;
    if (record.worst_group.empty() || g.total > record.worst_group_total) {
      record.worst_group = g.name;
      record.worst_group_total = g.total;
    }
  }
  return groups;
}

GroupTargetPlan plan_group_targets(const std::vector<GroupMeanError>& groups, double E, long rays, std::size_t room,
                                   std::vector<bool>& split, const std::vector<bool>& eligible, bool equal_share_floor) {
  GroupTargetPlan out;
  out.next_rays = rays;
  const double E_g = group_target(E);
  // Whether the next step splits in any case (the caller's marks, or a group above E_g): then the groups within E_g
  // are planned too, and those whose discretisation part is above 0.8 E_g (where the plan refines) are split now.
  bool splits_anyway = std::find(split.begin(), split.end(), true) != split.end();
  for (const GroupMeanError& g : groups) splits_anyway = splits_anyway || (g.counted && g.total > E_g);
  for (const GroupMeanError& g : groups) {
    if (!g.counted || (g.total <= E_g && !splits_anyway)) continue;
    const TargetErrorPlan own = plan_target_error_step(g.statistical, g.discretisation, E_g, rays);
    out.next_rays = std::max(out.next_rays, own.next_rays);
    if (!own.refine) continue;
    out.refine = true;
    // The shares add up to the error itself (not its square); a split is taken to halve a patch's share (as the
    // global rule takes it to halve a contribution: first order would quarter it, a patch across a shadow line only
    // halves it), so the marked shares f must satisfy f e_d / 2 >= e_d - t_d, t_d = 0.7 E_g the plan's target.
    const double fraction = std::min(1.0, 2 * (1 - kPlanTarget * E_g / g.discretisation));
    RADWALK_CHECK_EQ(g.share.size(), split.size());
    // equal_share_floor: the floor t_d / N (header); none where no share is above it.
    double floor = equal_share_floor ? kPlanTarget * E_g / double(split.size()) : 0.0;
    if (!(*std::max_element(g.share.begin(), g.share.end()) > floor)) floor = 0;
    out.marked += mark_largest(g.share, fraction, floor, eligible, room - out.marked, split);
  }
  return out;
}

TargetErrorResult solve_to_target_error(PatchSet patches, const TargetErrorWork& work, const TargetErrorOptions& options,
                                        const std::function<void(const TargetErrorStep&, int step)>& on_step) {
  const double E = options.target;
  if (!(E > 0 && E < 1)) throw InputError("the target error must be in (0, 1), got " + std::to_string(E));
  if (options.rays < 1) throw InputError("the target error's rays per patch must be >= 1");
  if (!(options.max_seconds >= 0)) throw InputError("the target error's time budget must be >= 0 seconds");
  if (!options.each.empty() && options.each != "material" && options.each != "object" && options.each != "group")
    throw InputError("the target error's groups must be material, object or group, got '" + options.each + "'");
  if (options.max_patches < patches.size())
    throw InputError("the patch budget " + std::to_string(options.max_patches) + " is below the scene's " +
                     std::to_string(patches.size()) + " patches");
  Timer run;
  TargetErrorResult out;
  long rays = options.rays;
  if (options.start_patches > 0) patches = split_to_start(std::move(patches), options);
  for (int step = 0;; ++step) {
    Timer timer;
    TargetErrorStage stage = work(patches, rays, step);
    const Solution& solution = stage.solution;
    const bool solved = solution.status == SolveStatus::converged &&
                        solution.B.rows() == static_cast<Eigen::Index>(patches.size());
    if (solved && solution.B_disc.rows() != solution.B.rows())
      throw InputError("the target error needs the discretisation estimate, which this step did not give");
    TargetErrorStep s;
    s.patches = patches.size();
    s.rays_per_patch = rays;
    if (solved) {
      s.statistical = solution.B_se.size() ? relative_error(patches, solution.B, solution.B_se) : 0.0;
      s.discretisation = relative_error(patches, solution.B, solution.B_disc);
      s.total = relative_error(patches, solution.B, total_error(solution.B_se, solution.B_disc));
    }
    const std::vector<GroupMeanError> groups =
        solved ? step_group_errors(patches, stage, solution.B, solution.B_se, options.each, E, s)
               : std::vector<GroupMeanError>();
    s.seconds = timer.seconds();

    // Stop, or plan the next step.
    std::string stop;
    std::vector<bool> split;
    long next_rays = rays;
    if (!solved) {
      stop = "solver";
    } else if (s.total <= E && s.groups_within == s.groups) {
      stop = "target reached";
    } else if (step + 1 >= options.max_steps) {
      stop = "max-steps";
    } else {
      // The global plan where the per-patch target is missed, then each group's above E.
      const TargetErrorPlan plan = s.total > E ? plan_target_error_step(s.statistical, s.discretisation, E, rays)
                                               : TargetErrorPlan{false, 0, rays};
      bool refine = plan.refine;
      next_rays = plan.next_rays;
      const std::size_t room = (options.max_patches - patches.size()) / 3;
      std::size_t marked = 0;
      split.assign(patches.size(), false);
      if (refine) {
        split = patches_to_split(patches, solution.B_disc, stage.shooter_share, plan.split_fraction, room);
        marked = static_cast<std::size_t>(std::count(split.begin(), split.end(), true));
      }
      if (!groups.empty()) {
        const GroupTargetPlan own = plan_group_targets(groups, E, rays, room - marked, split);
        next_rays = std::max(next_rays, own.next_rays);
        refine = refine || own.refine;
        marked += own.marked;
      }
      const bool more_rays = next_rays > rays;
      if (refine && marked == 0 && !more_rays) {
        stop = "max-patches";
      } else if (!refine && !more_rays) {
        stop = "rays";  // at their bound
      } else if (options.max_seconds > 0) {
        const double next = double(patches.size() + 3 * marked) * double(next_rays);
        const double predicted = s.seconds * next / (double(patches.size()) * double(rays));
        if (run.seconds() + predicted > options.max_seconds) stop = "max-seconds";
      }
      if (stop.empty()) {
        s.split = marked;
        s.next_rays_per_patch = next_rays;
      }
    }
    out.steps.push_back(s);
    if (on_step) on_step(s, step);
    if (!stop.empty()) {
      out.reached = stop == "target reached";
      out.stop_reason = stop;
      out.patches = std::move(patches);
      out.form_factors = std::move(stage.form_factors);
      out.solution = std::move(stage.solution);
      out.groups = groups;
      break;
    }
    if (s.split > 0) patches = split_patches(patches, split);
    rays = next_rays;
  }
  out.seconds = run.seconds();
  return out;
}

}  // namespace radwalk
