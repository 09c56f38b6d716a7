#include "walk/walk_method.h"

#include "core/did_you_mean.h"
#include "core/error.h"
#include "walk/named_choice.h"

namespace radwalk {

std::vector<WalkMethod> all_walk_methods() {
  std::vector<WalkMethod> methods;
  for (const WalkMethodRow& row : kWalkMethods) methods.push_back(row.method);
  return methods;
}

std::vector<std::string> walk_method_names() { return choice_names(kWalkMethods); }

std::vector<std::string> estimator_names(WalkDirection direction) {
  std::vector<std::string> names;
  for (const WalkMethodRow& row : kWalkMethods)
    if (row.direction == direction) names.emplace_back(row.estimator);
  return names;
}

WalkMethod parse_walk_method(std::string_view name) { return find_choice(kWalkMethods, name, "method").method; }

WalkDirection parse_walk_direction(std::string_view name) {
  return find_choice(kWalkDirections, name, "walk direction").value;
}

WalkMethod walk_method(WalkDirection direction, std::string_view estimator) {
  for (const WalkMethodRow& row : kWalkMethods)
    if (row.direction == direction && row.estimator == estimator) return row.method;
  const std::vector<std::string> names = estimator_names(direction);
  const std::string given(estimator), walks = std::string(direction_name(direction)) + "ing walks";
  for (const WalkMethodRow& row : kWalkMethods)
    if (row.estimator == estimator)
      throw InputError("random walk: estimator '" + given + "' is not available for " + walks + " (valid: " +
                       join_names(names) + "; '" + given + "' is an estimator of " +
                       std::string(direction_name(row.direction)) + "ing walks)");
  throw InputError("random walk: unknown estimator '" + given + "' for " + walks + " (valid: " + join_names(names) +
                   ")" + did_you_mean(given, names));
}

}  // namespace radwalk
