// --target-error through the hierarchy (hierarchy/hierarchical_target_error.h), on the block room of
// test_estimate_refinement.cpp (a block standing on the floor of a room lit from the ceiling):
//   - the run to 5 %: reached, the last step's estimate at most the target, and every step after the first is
//     what the previous step's plan (solve/target_error.h, plan_target_error_step) asked for: leaves + 3 x split,
//     the planned rays; a step splits leaves exactly when the plan refines;
//   - the answer's face averages agree with the path tracer's within their stated errors: per input face and
//     channel |mean of the leaves - B_pt| <= z_crit sqrt(se_h^2 + se_pt^2 + disc^2) (se_h, disc: the leaves'
//     B_se and B_disc summed over the face, a bound whatever their correlation; z_crit Sidak at family-wise 1e-3
//     over the faces and channels);
//   - the budgets stop a run whose target is out of reach: the leaves within max_leaves, and no step started that
//     the time budget predicts would pass it ("max-seconds"), not reached;
//   - options out of range are refused;
//   - the two transports (hierarchical stochastic Jacobi, and the leaves solved as patches by traced form factors)
//     estimate the same leaves' B: on the same starting tree, per leaf |B_ff - B_rays| <= t_crit sqrt(se_ff^2 +
//     se_rays^2), t_crit Student's t with the rays' replicates - 1 degrees of freedom (its B_se is their spread)
//     at a family-wise significance of 1e-3 over the leaves (Sidak), one channel (the room is grey).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.h"
#include "formfactor/emitter_form_factors.h"
#include "solve/discretisation_error.h"
#include "solve/form_factor_error.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "hierarchy/estimate_refinement.h"
#include "hierarchy/hierarchical_target_error.h"
#include "hierarchy/leaf_patches.h"
#include "hierarchy/start_by_edge_length.h"
#include "pathtrace/patch_average.h"
#include "patch/patch_builder.h"
#include "support/box_scenes.h"
#include "support/statistics.h"
#include "visibility/embree_visibility.h"

using namespace radwalk;

namespace {

PatchSet block_room() {
  PatchBuilder b;
  const int wall = b.add_material("wall", Rgb::Constant(0.6));
  const int light = b.add_material("light", Rgb::Zero(), Rgb::Constant(10.0));
  const int block = b.add_material("block", Rgb::Constant(0.5));
  test::add_box(b, Vec3(0, 0, 0), Vec3(2, 2, 2), 1, true, wall);
  b.add_quad(Vec3(0.75, 0.75, 1.99), Vec3(0.75, 1.25, 1.99), Vec3(1.25, 1.25, 1.99), Vec3(1.25, 0.75, 1.99), light);
  test::add_box(b, Vec3(0.6, 0.6, 0), Vec3(1.4, 1.4, 0.5), 1, false, block);
  return b.build();
}

HierarchicalOptions solve_options(std::uint64_t seed) {
  HierarchicalOptions o;
  o.max_level = 6;
  o.replicates = 4;
  o.seed = seed;
  return o;
}

// The uniform route's work on given patches (the CLI's recommended route: Sobol rays, the emitter columns chosen
// automatically, the automatic solver; B_se from F's noise, B_disc the discretisation estimate).
TargetErrorStage form_factor_step(const PatchSet& p, long rays, std::uint64_t seed) {
  TargetErrorStage stage;
  const EmbreeVisibility visibility(p);
  FormFactorOptions o;
  o.rays_per_patch = rays;
  o.seed = seed;
  o.sobol = true;
  stage.form_factors = estimate_form_factors_with_emitters(p, visibility, o, kAutoEmitterSamples);
  const RadiosityProblem problem = make_problem(p, SparseF(stage.form_factors.F));
  SolveOptions s;
  s.max_iterations = default_max_iterations(s.solver, p.size());
  stage.solution = solve_radiosity(problem, s);
  stage.solution.B_se = form_factor_error(p, visibility, stage.form_factors, problem, stage.solution.B).standard_error;
  stage.solution.B_disc = discretisation_error(p, visibility, problem, stage.solution.B, 4, seed).standard_error;
  return stage;
}

// Student's t two-sided critical value at significance alpha with nu degrees of freedom, by the Cornish-Fisher
// expansion about the normal quantile z (Abramowitz and Stegun 26.7.5, three terms; for nu >= 30 and z <= 5 its
// error is below 0.01).
double t_critical(double alpha, double nu) {
  const double z = z_critical(alpha);
  const double z3 = z * z * z, z5 = z3 * z * z;
  return z + (z3 + z) / (4 * nu) + (5 * z5 + 16 * z3 + 3 * z) / (96 * nu * nu);
}

// A target out of reach and one step (max_steps): a single solve on the starting tree of start_leaves.
HierarchicalTargetOptions one_step_on_the_start(long rays_per_leaf, std::size_t start_leaves, int directions) {
  HierarchicalTargetOptions o;
  o.target = 0.001;
  o.max_steps = 1;
  o.rays_per_leaf = rays_per_leaf;
  o.start_leaves = start_leaves;
  o.directions = directions;
  return o;
}

}  // namespace

TEST_CASE("hierarchical target error: the two transports give the same leaves' B within their errors",
          "[hierarchy][target_error]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  const HierarchicalTargetOptions o = one_step_on_the_start(2000, 150, 4);
  HierarchicalOptions h = solve_options(5);
  h.replicates = 40;
  const HierarchicalTargetResult rays = solve_hierarchical_to_target_error(roots, visibility, h, o);
  const TargetErrorWork work = [](const PatchSet& p, long r, int) { return form_factor_step(p, r, 17); };
  const HierarchicalTargetResult ff = solve_hierarchical_to_target_error(roots, visibility, h, o, {}, work);
  REQUIRE(ff.form_factor_transport);
  REQUIRE_FALSE(rays.form_factor_transport);
  CHECK(ff.stop_reason == "max-steps");
  REQUIRE(ff.solution.leaves == rays.solution.leaves);  // the same tree
  const PatchSet leaves = leaf_patches(roots, ff.solution.tree, ff.solution.leaves);
  REQUIRE(leaves.size() > 100);
  // The answer is the leaf solver's, row for row.
  const Solution answer = hierarchical_target_solution(ff);
  CHECK(answer.B.isApprox(ff.stage.solution.B));
  CHECK(ff.B_disc.isApprox(ff.stage.solution.B_disc));

  const double t_crit = t_critical(sidak(1e-3, leaves.size()), h.replicates - 1);
  double max_t = 0;
  std::size_t counted = 0;
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    if ((leaves.E[k] > 0).any()) continue;
    const auto i = static_cast<Eigen::Index>(k);
    const double d = ff.solution.B(i, 0) - rays.solution.B(i, 0);
    const double s = std::hypot(ff.solution.B_se(i, 0), rays.solution.B_se(i, 0));
    if (!(s > 0)) {  // a leaf no light reaches (the block's bottom on the floor): both exactly 0
      CHECK(std::abs(d) == 0);
      continue;
    }
    max_t = std::max(max_t, std::abs(d) / s);
    ++counted;
  }
  INFO(counted << " leaves: largest |t| " << max_t << ", t_crit " << t_crit << "; statistical error rays "
               << rays.steps[0].step.statistical << ", form factors " << ff.steps[0].step.statistical);
  CHECK(max_t <= t_crit);
  // The form-factor transport's statistical error is the smaller at equal rays (the reason it exists).
  CHECK(ff.steps[0].step.statistical < rays.steps[0].step.statistical);
}

TEST_CASE("hierarchical target error: the block room to 5 %, each step as planned, faces agree with the path tracer",
          "[hierarchy][target_error]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  HierarchicalTargetOptions o;
  o.target = 0.05;
  o.rays_per_leaf = 200;
  o.max_leaves = 4000;
  o.directions = 8;
  const HierarchicalTargetResult r = solve_hierarchical_to_target_error(roots, visibility, solve_options(3), o);
  for (const HierarchicalTargetStep& s : r.steps)
    UNSCOPED_INFO("leaves " << s.step.patches << ", rays a leaf " << s.step.rays_per_patch << ": total "
                            << s.step.total << " (statistical " << s.step.statistical << ", discretisation "
                            << s.step.discretisation << "), split " << s.step.split);
  REQUIRE(r.reached);
  CHECK(r.stop_reason == "target reached");
  REQUIRE(r.steps.size() >= 2);  // the input faces alone are far above 5 %
  CHECK(r.steps.back().step.total <= o.target);
  for (std::size_t k = 0; k + 1 < r.steps.size(); ++k) {
    const TargetErrorStep& a = r.steps[k].step;
    const TargetErrorStep& b = r.steps[k + 1].step;
    const TargetErrorPlan plan = plan_target_error_step(a.statistical, a.discretisation, o.target, a.rays_per_patch);
    CHECK(a.total > o.target);
    CHECK(b.patches == a.patches + 3 * a.split);
    CHECK(b.rays_per_patch == plan.next_rays);
    CHECK((a.split > 0) == plan.refine);
  }
  const HierarchicalResult& h = r.solution;
  REQUIRE(r.B_disc.rows() == h.B.rows());
  REQUIRE(static_cast<std::size_t>(h.B.rows()) == r.steps.back().step.patches);

  PatchAverageOptions pt;
  pt.spp = 1 << 15;
  pt.seed = 101;
  pt.progress = false;
  const Solution ref = estimate_patch_averages(roots, visibility, pt);
  const PatchSet leaves = leaf_patches(roots, h.tree, h.leaves);
  const std::size_t N = roots.size();
  std::vector<Rgb> sum(N, Rgb::Zero()), se(N, Rgb::Zero()), dsum(N, Rgb::Zero());
  for (std::size_t k = 0; k < leaves.size(); ++k) {
    const auto f = static_cast<std::size_t>(h.tree.root[static_cast<std::size_t>(h.leaves[k])]);
    const auto i = static_cast<Eigen::Index>(k);
    sum[f] += leaves.area[k] * h.B.row(i).transpose();
    se[f] += leaves.area[k] * h.B_se.row(i).transpose();
    dsum[f] += leaves.area[k] * r.B_disc.row(i).transpose();
  }
  const double z_crit = z_critical(sidak(1e-3, 3 * N));
  double max_z = 0;
  for (std::size_t f = 0; f < N; ++f) {
    if (!(roots.rho[f] > 0).any() || !(ref.B.row(static_cast<Eigen::Index>(f)).maxCoeff() > 0)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = sum[f](c) / roots.area[f] - ref.B(static_cast<Eigen::Index>(f), c);
      const double s_h = se[f](c) / roots.area[f], s_pt = ref.B_se(static_cast<Eigen::Index>(f), c);
      const double s_d = dsum[f](c) / roots.area[f];
      max_z = std::max(max_z, std::abs(d) / std::sqrt(s_h * s_h + s_pt * s_pt + s_d * s_d));
    }
  }
  INFO("largest z " << max_z << ", z_crit " << z_crit);
  CHECK(max_z <= z_crit);
}

TEST_CASE("hierarchical target error: the budgets stop an unreachable target", "[hierarchy][target_error]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  HierarchicalTargetOptions o;
  o.target = 0.001;
  o.rays_per_leaf = 100;
  o.max_leaves = static_cast<long>(roots.size()) + 40;
  o.directions = 4;
  o.max_seconds = 3;  // with the leaves at their budget the plan asks for ever more rays: the time stops it
  const HierarchicalTargetResult r = solve_hierarchical_to_target_error(roots, visibility, solve_options(4), o);
  for (const HierarchicalTargetStep& s : r.steps)
    UNSCOPED_INFO("leaves " << s.step.patches << ", rays a leaf " << s.step.rays_per_patch << ", " << s.step.seconds
                            << " s");
  CHECK_FALSE(r.reached);
  CHECK(r.stop_reason == "max-seconds");
  CHECK(static_cast<long>(r.solution.leaves.size()) <= o.max_leaves);
  CHECK(r.steps.back().step.total > o.target);
}

TEST_CASE("hierarchical target error: options out of range are refused", "[hierarchy][target_error]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  const auto refused = [&](void (*change)(HierarchicalTargetOptions&)) {
    HierarchicalTargetOptions o;
    change(o);
    CHECK_THROWS_AS(solve_hierarchical_to_target_error(roots, visibility, solve_options(1), o), InputError);
  };
  refused([](HierarchicalTargetOptions& o) { o.target = 0; });
  refused([](HierarchicalTargetOptions& o) { o.target = 1; });
  refused([](HierarchicalTargetOptions& o) { o.rays_per_leaf = 0; });
  refused([](HierarchicalTargetOptions& o) { o.max_leaves = 3; });
  refused([](HierarchicalTargetOptions& o) { o.points_side = 1; });
  refused([](HierarchicalTargetOptions& o) { o.bulk = 0; });
  refused([](HierarchicalTargetOptions& o) { o.bulk = 1.5; });
}

// Step 0 of a run far from its target on the block room (target 0.005, 400 start leaves), and what the split
// after it is measured against: the leaves' eta_l^2 recomputed from a run stopped after step 0 (the same seed: the
// same tree, B, B_disc and W2) and the equal share 0.49 E^2 sum A B^2 / N.
struct FarFromTarget {
  TargetErrorStep first;     // step 0 of the two-step run
  TargetErrorPlan plan;      // its plan
  std::vector<double> eta2;  // its leaves' receiver shares
  std::vector<bool> splittable;
  double share = 0;
};

FarFromTarget far_from_target(double bulk) {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  HierarchicalTargetOptions o;
  o.target = 0.005;
  o.max_steps = 2;
  o.rays_per_leaf = 200;
  o.start_leaves = 400;
  o.directions = 4;
  o.bulk = bulk;
  const HierarchicalOptions h = solve_options(6);
  const TargetErrorWork work = [](const PatchSet& p, long r, int) { return form_factor_step(p, r, 23); };
  const HierarchicalTargetResult r = solve_hierarchical_to_target_error(roots, visibility, h, o, {}, work);
  o.max_steps = 1;
  const HierarchicalTargetResult r0 = solve_hierarchical_to_target_error(roots, visibility, h, o, {}, work);
  REQUIRE(r.steps.size() == 2);
  FarFromTarget f;
  f.first = r.steps[0].step;
  f.plan = plan_target_error_step(f.first.statistical, f.first.discretisation, o.target, f.first.rays_per_patch);
  const HierarchicalResult& s0 = r0.solution;
  REQUIRE(s0.leaves.size() == f.first.patches);
  f.eta2 = leaf_error_indicator(roots, visibility, s0.tree, s0.leaves, s0.B, r0.B_disc, o.directions, o.points_side,
                                h.seed)
               .eta2;
  const PatchSet leaves = leaf_patches(roots, s0.tree, s0.leaves);
  double norm = 0;
  for (std::size_t k = 0; k < leaves.size(); ++k)
    if (!(leaves.E[k] > 0).any() && (leaves.rho[k] > 0).any())
      norm += leaves.area[k] * s0.B.row(static_cast<Eigen::Index>(k)).square().sum();
  f.share = 0.49 * o.target * o.target * norm / double(leaves.size());
  for (const ElementIndex e : s0.leaves)
    f.splittable.push_back(splittable(s0.tree, std::size_t(e), h));
  return f;
}

// With the estimated discretisation part at the target or above, the plan's share is 1 (solve/target_error.h):
// uncapped (bulk 1), the split must still leave alone the leaves within their equal share of the target, and be
// exactly the leaves above it, fewer than those with eta_l^2 > 0 (which the rule without the share split).
TEST_CASE("hierarchical target error: far from the target, leaves within their share are not split",
          "[hierarchy][target_error]") {
  const FarFromTarget f = far_from_target(1.0);
  REQUIRE(f.plan.refine);
  REQUIRE(f.plan.split_fraction == 1.0);
  std::size_t above = 0, positive = 0;
  for (const double e2 : f.eta2) above += e2 > f.share, positive += e2 > 0;
  INFO("leaves " << f.first.patches << ", e_d " << f.first.discretisation << ": split " << f.first.split
                 << ", above the share " << above << ", eta^2 > 0 " << positive);
  CHECK(f.first.split == above);
  CHECK(above < positive);
}

// Doerfler's marking (hierarchical_target_error.h, bulk): the same step with theta = 0.7 splits the fewest leaves,
// largest eta_l^2 first, that hold 0.7 of sum eta_l^2 (none within the share), fewer than the uncapped rule's.
TEST_CASE("hierarchical target error: far from the target, a step splits the fewest leaves holding theta of the "
          "error", "[hierarchy][target_error]") {
  const FarFromTarget f = far_from_target(0.7);
  REQUIRE(f.plan.split_fraction == 1.0);
  double total = 0, above = 0;
  for (const double e2 : f.eta2) total += std::max(e2, 0.0), above += e2 > f.share;
  std::vector<std::size_t> order(f.eta2.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return f.eta2[a] > f.eta2[b]; });
  std::size_t expected = 0;
  double held = 0;
  for (const std::size_t k : order) {
    if (!(f.eta2[k] > f.share) || held >= 0.7 * total) break;
    if (!f.splittable[k]) continue;
    ++expected;
    held += f.eta2[k];
  }
  INFO("leaves " << f.first.patches << ": split " << f.first.split << ", expected " << expected << ", above the share "
                 << above);
  CHECK(f.first.split == expected);
  CHECK(double(expected) < above);
  CHECK(held >= 0.7 * total);  // theta was reached before the share stopped the marks: the cap is what bound
}

// The start (hierarchy/start_by_edge_length.h, start_leaves): every leaf longer than L split, L the largest that gives
// at least the roots and start_leaves more. Deterministic: the first step's leaves number at least that many, and
// no leaf keeps more than half the longest root edge (the largest roots were split). A start that split nothing,
// or too little, fails the count.
TEST_CASE("hierarchical target error: the start splits by edge length to the roots and start_leaves more",
          "[hierarchy][target_error]") {
  const PatchSet roots = block_room();
  const EmbreeVisibility visibility(roots);
  HierarchicalTargetOptions o = one_step_on_the_start(50, 120, 2);
  o.split = "adaptive";
  const TargetErrorWork work = [](const PatchSet& p, long r, int) { return form_factor_step(p, r, 29); };
  const HierarchicalTargetResult r = solve_hierarchical_to_target_error(roots, visibility, solve_options(7), o, {}, work);
  REQUIRE(r.steps.size() == 1);
  const ElementTree& tree = r.solution.tree;
  INFO(roots.size() << " roots, " << r.solution.leaves.size() << " leaves");
  CHECK(r.solution.leaves.size() >= roots.size() + o.start_leaves);
  double longest_root = 0, longest_leaf = 0;
  for (std::size_t i = 0; i < roots.size(); ++i)
    for (int k = 0; k < roots.corner_count(i); ++k)
      longest_root = std::max(longest_root, (roots.corner(i, (k + 1) % roots.corner_count(i)) - roots.corner(i, k)).norm());
  for (const ElementIndex e : r.solution.leaves)
    for (int k = 0; k < tree.corner_count[std::size_t(e)]; ++k) {
      const auto& c = tree.corner[std::size_t(e)];
      longest_leaf = std::max(longest_leaf, (c[(k + 1) % tree.corner_count[std::size_t(e)]] - c[k]).norm());
    }
  CHECK(longest_leaf <= 0.5 * longest_root + 1e-9);
}
