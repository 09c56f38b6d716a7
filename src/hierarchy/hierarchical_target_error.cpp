#include "hierarchy/hierarchical_target_error.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <utility>

#include "core/error.h"
#include "core/timer.h"
#include "hierarchy/direct_refinement.h"
#include "hierarchy/estimate_refinement.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/leaf_variation.h"
#include "hierarchy/split_kind.h"
#include "hierarchy/start_by_edge_length.h"
#include "solve/discretisation_error.h"
#include "solve/refinement_marks.h"

namespace radwalk {
namespace {

constexpr int kMaxPointsSide = 64;  // 4096 direct-light points per leaf at most

// The leaf rows to split (solve/refinement_marks.h): by eta_l^2 and by the shooter shares (when estimated), each
// until its marked leaves hold `fraction` of its sum or the next is at most `floor`, at most `room` leaves, only
// splittable ones.
std::vector<std::size_t> leaves_to_split(const ElementTree& tree, const std::vector<ElementIndex>& leaves,
                                         const std::vector<double>& eta2, const std::vector<double>& shooter,
                                         double fraction, double floor, std::size_t room,
                                         const HierarchicalOptions& solve) {
  std::vector<bool> can(leaves.size());
  for (std::size_t k = 0; k < leaves.size(); ++k) can[k] = splittable(tree, static_cast<std::size_t>(leaves[k]), solve);
  const std::vector<bool> marks =
      refinement_marks(eta2, shooter.size() == leaves.size() ? shooter : std::vector<double>{}, fraction, floor, room, can);
  std::vector<std::size_t> split;
  for (std::size_t k = 0; k < marks.size(); ++k)
    if (marks[k]) split.push_back(k);
  return split;
}

}  // namespace

HierarchicalTargetResult solve_hierarchical_to_target_error(
    const PatchSet& roots, const Visibility& visibility, const HierarchicalOptions& solve,
    const HierarchicalTargetOptions& o, const std::function<void(const HierarchicalTargetStep&, int step)>& on_step,
    const TargetErrorWork& leaf_work) {
  const double E = o.target;
  if (!(E > 0 && E < 1)) throw InputError("the target error must be in (0, 1), got " + std::to_string(E));
  if (o.rays_per_leaf < 1) throw InputError("the target error's rays per leaf must be >= 1");
  if (!(o.max_seconds >= 0)) throw InputError("the target error's time budget must be >= 0 seconds");
  if (o.max_steps < 1) throw InputError("the target error's steps must be >= 1");
  if (!(o.bulk > 0 && o.bulk <= 1))
    throw InputError("the hierarchical target error's bulk parameter must be in (0, 1], got " + std::to_string(o.bulk));
  if (o.directions < 1 || o.points_side < 2)
    throw InputError("the hierarchical target error's estimate needs directions >= 1 and points per side >= 2");
  if (!o.each.empty() && o.each != "material" && o.each != "object" && o.each != "group")
    throw InputError("the target error's groups must be material, object or group, got '" + o.each + "'");
  if (!o.each.empty() && !leaf_work)
    throw InputError("the hierarchical target error per " + o.each + " needs the form-factor transport: the rays "
                     "transport stores no F for the adjoint of a group's mean");
  if (o.split != "regular" && o.split != "adaptive")
    throw InputError("the hierarchical split must be regular or adaptive, got '" + o.split + "'");
  if (o.max_leaves < static_cast<long>(roots.size()))
    throw InputError("the leaf budget " + std::to_string(o.max_leaves) + " is below the scene's " +
                     std::to_string(roots.size()) + " patches");
  const Timer run;
  HierarchicalTargetResult out;
  ElementTree tree = start_by_edge_length(roots, o.start_leaves, o.max_leaves, o.split == "adaptive", solve);
  long rays = o.rays_per_leaf;
  const std::size_t emitters = std::max<std::size_t>(1, emitter_roots(roots).size());
  for (int s = 0;; ++s) {
    const Timer timer;
    HierarchicalOptions so = solve;
    so.direct_oracle = so.transport_oracle = false;
    const auto leaves_now = static_cast<long>(tree.leaves().size());
    so.particles = rays * leaves_now;
    // The direct light's variance falls as 1 / M, not with the rays: M = m^2 >= R / (2 K), as many shadow rays
    // (2 per point and emitter) as the shooting's rays a leaf.
    so.points_side = std::clamp(static_cast<int>(std::ceil(std::sqrt(double(rays) / (2.0 * double(emitters))))),
                                solve.points_side, std::max(solve.points_side, kMaxPointsSide));
    so.seed = solve.seed + 7919 * static_cast<std::uint64_t>(s);
    HierarchicalResult h;
    TargetErrorStage stage;
    LeafErrorIndicator ind;
    bool solved = true;
    std::unique_ptr<Timer> estimate_timer;
    if (leaf_work) {
      // Form factors: the leaves as patches, solved and estimated as the uniform route's patches.
      h.leaves = tree.leaves();
      h.tree = std::move(tree);
      stage = leaf_work(leaf_patches(roots, h.tree, h.leaves), rays, s);
      const Solution& x = stage.solution;
      solved = x.status == SolveStatus::converged && x.B.rows() == static_cast<Eigen::Index>(h.leaves.size());
      if (solved && (x.B_disc.rows() != x.B.rows() || x.B_se.rows() != x.B.rows()))
        throw InputError("the hierarchical target error needs B_se and B_disc from its leaf solver, which this step "
                         "did not give");
      h.B = x.B;
      h.B_se = x.B_se;
      h.var = x.var;
      h.rays = rays * leaves_now;
      h.seconds = x.seconds;
      h.memory_bytes = h.tree.memory_bytes() + stage.form_factors.F.nonZeros() * (sizeof(double) + sizeof(int));
      estimate_timer = std::make_unique<Timer>();
      if (solved && stage.shooter_share.size() == h.leaves.size()) {
        ind.B_disc = x.B_disc;  // with the shooters' shares the within-leaf variation is not needed (below)
      } else if (solved) {
        ind = leaf_error_indicator(roots, visibility, h.tree, h.leaves, h.B, x.B_disc, o.directions, o.points_side,
                                   so.seed);
      }
    } else {
      h = solve_hierarchical(roots, visibility, std::move(tree), so);
      estimate_timer = std::make_unique<Timer>();
      ind = estimate_leaf_errors(roots, visibility, h, o.directions, o.points_side, so.seed, true);
    }
    const PatchSet leaves = leaf_patches(roots, h.tree, h.leaves);

    HierarchicalTargetStep record;
    TargetErrorStep& st = record.step;
    st.patches = h.leaves.size();
    st.rays_per_patch = rays;
    if (solved) {
      st.statistical = relative_error(leaves, h.B, h.B_se);
      st.discretisation = relative_error(leaves, h.B, ind.B_disc);
      st.total = relative_error(leaves, h.B, total_error(h.B_se, ind.B_disc));
    }
    // With the form-factor transport only (checked above): the stage holds F and the source.
    std::vector<GroupMeanError> groups =
        solved ? step_group_errors(leaves, stage, h.B, h.B_se, o.each, E, st) : std::vector<GroupMeanError>();
    record.rays = h.rays + h.shadow_rays + ind.rays + stage.estimate_rays;
    record.estimate_seconds = estimate_timer->seconds();
    st.seconds = timer.seconds();

    // Stop, or plan the next step.
    std::string stop;
    std::vector<std::size_t> split;  // leaf rows to split
    long next_rays = rays;
    if (!solved) {
      stop = "solver";
    } else if (st.total <= E && st.groups_within == st.groups) {
      stop = "target reached";
    } else if (s + 1 >= o.max_steps) {
      stop = "max-steps";
    } else {
      // The global plan where the per-leaf target is missed, then each group's above E.
      const TargetErrorPlan plan = st.total > E ? plan_target_error_step(st.statistical, st.discretisation, E, rays)
                                                : TargetErrorPlan{false, 0, rays};
      next_rays = plan.next_rays;
      bool refine = plan.refine;
      if (plan.refine) {
        // The largest eta_l^2 (and the largest shooter shares, where estimated: solve/refinement_marks.h) first
        // until they hold the plan's share of their sums, at most theta (o.bulk: Doerfler's marking, header).
        // A leaf already within its equal share of the discretisation target, eta_l^2 <= t_d^2 sum_l A_l |B_l|^2 / N
        // (t_d = kPlanTarget E, the plan's; N the leaves now), is never split: the optimal mesh equidistributes
        // eta_l^2, and when the plan's share is 1 (e_d far above the target) the rule alone would split every leaf,
        // however concentrated the error (the spot-lit room: 90 % of sum eta_l^2 in 2 of 690 leaves).
        double norm = 0;
        for (std::size_t k = 0; k < leaves.size(); ++k)
          if (!(leaves.E[k] > 0).any() && (leaves.rho[k] > 0).any())
            norm += leaves.area[k] * h.B.row(static_cast<Eigen::Index>(k)).square().sum();
        const double t_d = kPlanTarget * E;
        const double share = t_d * t_d * norm / double(leaves_now);
        // The receiver share: eta_l^2, or A_l |B_disc_l|^2 where the shooter shares are estimated (they hold the
        // part of the within-leaf variation that the leaves' averages see: docs/theory/discretisation_error.md,
        // "Refinement by both shares").
        const std::vector<double>& shooter = leaf_work ? stage.shooter_share : ind.shooter_share;
        std::vector<double> receiver = ind.eta2;
        if (shooter.size() == leaves.size()) {
          receiver.assign(leaves.size(), 0.0);
          for (std::size_t k = 0; k < leaves.size(); ++k)
            receiver[k] = !(leaves.E[k] > 0).any() && (leaves.rho[k] > 0).any()
                              ? leaves.area[k] * ind.B_disc.row(static_cast<Eigen::Index>(k)).square().sum()
                              : 0.0;
        }
        split = leaves_to_split(h.tree, h.leaves, receiver, shooter, std::min(plan.split_fraction, o.bulk), share,
                                static_cast<std::size_t>(std::max(0L, o.max_leaves - leaves_now)) / 3, solve);
      }
      if (!groups.empty()) {
        std::vector<bool> marks(leaves.size(), false), eligible(leaves.size(), false);
        for (std::size_t k = 0; k < leaves.size(); ++k)
          eligible[k] = splittable(h.tree, static_cast<std::size_t>(h.leaves[k]), solve);
        for (const std::size_t k : split) marks[k] = true;
        const long room = std::max(0L, (o.max_leaves - leaves_now) / 3 - static_cast<long>(split.size()));
        const GroupTargetPlan own = plan_group_targets(groups, E, rays, static_cast<std::size_t>(room), marks, eligible,
                                                         true);
        next_rays = std::max(next_rays, own.next_rays);
        refine = refine || own.refine;
        split.clear();
        for (std::size_t k = 0; k < marks.size(); ++k)
          if (marks[k]) split.push_back(k);
      }
      const bool more_rays = next_rays > rays;
      if (refine && split.empty() && !more_rays) {
        stop = (o.max_leaves - leaves_now) / 3 > 0 ? "depth" : "max-leaves";
      } else if (!refine && !more_rays) {
        stop = "rays";
      } else if (o.max_seconds > 0) {
        const double next = double(leaves_now + 3 * static_cast<long>(split.size())) * double(next_rays);
        const double predicted = st.seconds * next / (double(leaves_now) * double(rays));
        if (run.seconds() + predicted > o.max_seconds) stop = "max-seconds";
      }
      if (stop.empty()) {
        st.split = split.size();
        st.next_rays_per_patch = next_rays;
      }
    }
    // The kind of each split: regular, or from the marked leaves' directional variation (adaptive).
    std::vector<SplitKind> kinds(split.size(), SplitKind::regular);
    if (stop.empty() && o.split == "adaptive" && !split.empty()) {
      const Timer kind_timer;
      std::vector<ElementIndex> marked(split.size());
      for (std::size_t i = 0; i < split.size(); ++i) marked[i] = h.leaves[split[i]];
      const DirectionalVariation d = leaf_directional_variation(
          roots, visibility, h.tree, h.leaves, h.B, marked, std::max(o.points_side, 4), o.directions, so.seed + 1);
      for (std::size_t i = 0; i < split.size(); ++i) {
        kinds[i] = choose_split_kind(h.tree, static_cast<std::size_t>(marked[i]), d.along_01[i], d.along_03[i]);
        if (kinds[i] != SplitKind::regular) ++record.band_splits;
      }
      record.rays += d.rays;
      record.estimate_seconds += kind_timer.seconds();
      st.seconds += kind_timer.seconds();
    }
    out.steps.push_back(record);
    if (on_step) on_step(record, s);
    if (!stop.empty()) {
      out.reached = stop == "target reached";
      out.stop_reason = stop;
      out.B_disc = ind.B_disc;
      out.groups = std::move(groups);
      out.solution = std::move(h);
      out.form_factor_transport = static_cast<bool>(leaf_work);
      out.stage = std::move(stage);
      out.stage.problem.reset();  // its copy of F is not needed past the step
      break;
    }
    tree = std::move(h.tree);
    for (std::size_t i = 0; i < split.size(); ++i) tree.split(static_cast<std::size_t>(h.leaves[split[i]]), kinds[i]);
    rays = next_rays;
  }
  out.seconds = run.seconds();
  return out;
}

Solution hierarchical_target_solution(const HierarchicalTargetResult& r) {
  if (r.form_factor_transport) return r.stage.solution;
  Solution solution;
  solution.method = "hierarchical-jacobi";
  solution.status = SolveStatus::converged;
  solution.message = "unshot power below 1e-6 of the first shot's, or 200 iterations per replicate";
  solution.B = r.solution.B;
  solution.B_se = r.solution.B_se;
  solution.B_disc = r.B_disc;
  solution.var = r.solution.var;
  solution.walks = r.solution.rays;
  solution.iterations = r.solution.iterations;
  solution.seconds = r.solution.seconds;
  solution.info["shadow_rays"] = static_cast<double>(r.solution.shadow_rays);
  return solution;
}

}  // namespace radwalk
