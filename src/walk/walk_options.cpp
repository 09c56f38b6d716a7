#include "walk/walk_options.h"

#include <algorithm>

#include <string>

#include "core/error.h"
#include "walk/named_choice.h"

namespace radwalk {

WalkKernel parse_walk_kernel(std::string_view name) { return find_choice(kWalkKernels, name, "kernel").value; }

WalkSampler parse_walk_sampler(std::string_view name) { return find_choice(kWalkSamplers, name, "sampler").value; }

void check_walk_options(const WalkOptions& options, std::size_t patch_count) {
  const bool gather = is_gathering(options.method);
  if (gather && options.sampler != WalkSampler::random)
    throw InputError("random walk: --sampler " + std::string(sampler_name(options.sampler)) +
                     " is for shooting methods (--walk shoot); gathering walks use --sampler random");
  if (options.control_variate && !gather)
    throw InputError("random walk: --control-variate is for gathering methods (--walk gather)");
  if (options.direct_light && options.sampler == WalkSampler::random)
    throw InputError("random walk: --direct-light needs --sampler sobol or jacobi (and a shooting method)");
  if (options.sampler == WalkSampler::jacobi && options.method != WalkMethod::shoot_collision)
    throw InputError("random walk: --sampler jacobi scores every arrival (use --walk shoot --estimator collision)");
  if (options.sampler != WalkSampler::random) {
    if (options.replicates < 2)
      throw InputError("random walk: --replicates " + std::to_string(options.replicates) +
                       " (need at least 2 for a standard error)");
    if (options.particles < 2L * options.replicates)
      throw InputError("random walk: " + std::to_string(options.particles) + " particles for " +
                       std::to_string(options.replicates) + " replicates (need at least 2 per replicate)");
  }
  if (options.shadow_rays < 0)
    throw InputError("random walk: --shadow-rays " + std::to_string(options.shadow_rays) + " is negative");
  const long count = gather ? options.walks_per_patch : options.particles;
  if (count < 2)
    throw InputError("random walk: " + std::string(gather ? "walks per patch" : "particles") + " = " +
                     std::to_string(count) + " (need at least 2 for a variance estimate)");
  if (count > kMaxWalkCount || (gather && static_cast<double>(count) * static_cast<double>(patch_count) >
                                               static_cast<double>(kMaxWalkCount)))
    throw InputError("random walk: " + std::string(gather ? "walks per patch" : "particles") + " = " +
                     std::to_string(count) + (gather ? " x " + std::to_string(patch_count) + " patches" : "") +
                     " is more than the " + std::to_string(kMaxWalkCount) + " walks radwalk counts in one run");
  check_survival(options.survival);
  // P12: a patch listed twice would be estimated twice and reported once.
  std::vector<int> sorted = options.patches;
  std::sort(sorted.begin(), sorted.end());
  const auto repeat = std::adjacent_find(sorted.begin(), sorted.end());
  if (repeat != sorted.end())
    throw InputError("random walk: patch " + std::to_string(*repeat) + " is listed more than once in --patches");
  for (int i : options.patches)
    if (i < 0 || static_cast<std::size_t>(i) >= patch_count)
      throw InputError("random walk: patch " + std::to_string(i) + " is out of range (there are " +
                       std::to_string(patch_count) + " patches)");
}

long total_walks(const WalkOptions& options, std::size_t patch_count) {
  if (!is_gathering(options.method)) return options.particles;
  const std::size_t estimated = options.patches.empty() ? patch_count : options.patches.size();
  return options.walks_per_patch * static_cast<long>(estimated);
}

}  // namespace radwalk
