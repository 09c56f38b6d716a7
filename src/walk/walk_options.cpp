#include "walk/walk_options.h"

#include "core/error.h"

namespace radwalk {

const std::vector<std::string>& walk_methods() {
  static const std::vector<std::string> names = {"gather-absorption", "gather-collision", "gather-expected-value",
                                                 "shoot-collision",   "shoot-absorption", "shoot-survival"};
  return names;
}

std::string method_name(const WalkOptions& options) { return options.walk + "-" + options.estimator; }

namespace {
std::string method_list() {
  std::string s;
  for (const auto& m : walk_methods()) s += (s.empty() ? "" : ", ") + m;
  return s;
}
}  // namespace

void set_method(WalkOptions& options, const std::string& method) {
  for (const auto& m : walk_methods())
    if (m == method) {
      const auto dash = m.find('-');
      options.walk = m.substr(0, dash);
      options.estimator = m.substr(dash + 1);
      return;
    }
  throw InputError("random walk: unknown method '" + method + "' (use one of " + method_list() + ")");
}

void check_walk_options(const WalkOptions& options, std::size_t patch_count) {
  if (options.walk != "gather" && options.walk != "shoot")
    throw InputError("random walk: walk '" + options.walk + "' is neither 'gather' nor 'shoot'");
  bool known = false;
  for (const auto& m : walk_methods()) known = known || m == method_name(options);
  if (!known)
    throw InputError("random walk: estimator '" + options.estimator + "' is not available for " + options.walk +
                     "ing walks (valid methods: " + method_list() + ")");
  if (options.kernel != "matrix" && options.kernel != "ray")
    throw InputError("random walk: kernel '" + options.kernel + "' is neither 'matrix' nor 'ray'");
  if (options.walks < 2)
    throw InputError("random walk: walks = " + std::to_string(options.walks) +
                     " (need at least 2 for a variance estimate)");
  if (options.survival == "constant" && !(options.survival_constant > 0 && options.survival_constant < 1))
    throw InputError("random walk: survival constant " + std::to_string(options.survival_constant) +
                     " is not in (0, 1)");
  for (int i : options.patches)
    if (i < 0 || static_cast<std::size_t>(i) >= patch_count)
      throw InputError("random walk: patch " + std::to_string(i) + " is out of range (there are " +
                       std::to_string(patch_count) + " patches)");
}

GatherEstimator gather_estimator(const WalkOptions& options) {
  if (options.estimator == "absorption") return GatherEstimator::absorption;
  if (options.estimator == "collision") return GatherEstimator::collision;
  if (options.estimator == "expected-value") return GatherEstimator::expected_value;
  throw InputError("random walk: '" + options.estimator + "' is not a gathering estimator");
}

ShootEstimator shoot_estimator(const WalkOptions& options) {
  if (options.estimator == "collision") return ShootEstimator::collision;
  if (options.estimator == "absorption") return ShootEstimator::absorption;
  if (options.estimator == "survival") return ShootEstimator::survival;
  throw InputError("random walk: '" + options.estimator + "' is not a shooting estimator");
}

}  // namespace radwalk
