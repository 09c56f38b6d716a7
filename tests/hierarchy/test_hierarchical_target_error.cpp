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
//   - options out of range are refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/error.h"
#include "hierarchy/hierarchical_target_error.h"
#include "hierarchy/leaf_patches.h"
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

}  // namespace

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
}
