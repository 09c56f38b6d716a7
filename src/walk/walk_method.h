#pragma once
// The random-walk methods: the only list of them. A method is a walk direction and an estimator:
//   gathering (adjoint) walks start at the patch i they estimate and score B_i (gather_estimators.h);
//   shooting (forward) particles start at the emitters and score the reflected power of every patch they reach
//   (shoot_estimators.h).
// kWalkMethods holds one row per method, in the order of the enum: the name the CLI, the CSV, the JSON and the VTK
// field names use ("gather-collision"), its direction, the estimator's name within that direction (the CLI's
// --estimator) and a line for help texts. Every name a user types is parsed here, with a one-line refusal that
// lists the valid names and suggests the nearest (named_choice.h).
//
// Adding an estimator is one class (with its tables, its walk or particle state machine and its second-moment
// source term, next to the others in gather_estimators.h or shoot_estimators.h, registered as EstimatorOf<method>)
// plus one row here (with its enum name). with_estimator (walk_estimators.h) is the one dispatch from a method to
// its class: the solver, the exact variance, the comparison and the tests all go through it.
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "walk/named_choice.h"

namespace radwalk {

enum class WalkDirection { gather, shoot };

enum class WalkMethod {
  gather_absorption,
  gather_collision,
  gather_expected_value,
  shoot_collision,
  shoot_absorption,
  shoot_survival,
};

struct WalkMethodRow {
  WalkMethod method;
  std::string_view name;       // "gather-collision"
  WalkDirection direction;
  std::string_view estimator;  // "collision": the name within its direction
  std::string_view scores;     // what one walk or particle scores (help texts)
};

inline constexpr auto kWalkMethods = std::to_array<WalkMethodRow>({
    {WalkMethod::gather_absorption, "gather-absorption", WalkDirection::gather, "absorption",
     "W E_k / q_k at the patch k where the walk stops (von Neumann-Ulam)"},
    {WalkMethod::gather_collision, "gather-collision", WalkDirection::gather, "collision",
     "W E_k at every patch visited, the start included (Wasow)"},
    {WalkMethod::gather_expected_value, "gather-expected-value", WalkDirection::gather, "expected-value",
     "E_i + W (H E)_k at every patch visited (next-event estimation)"},
    {WalkMethod::shoot_collision, "shoot-collision", WalkDirection::shoot, "collision",
     "every arrival at a patch scores its power there"},
    {WalkMethod::shoot_absorption, "shoot-absorption", WalkDirection::shoot, "absorption",
     "the arrival where the particle is absorbed, over the absorption probability"},
    {WalkMethod::shoot_survival, "shoot-survival", WalkDirection::shoot, "survival",
     "the arrivals where the particle survives, over the survival probability"},
});

inline constexpr std::array<NamedChoice<WalkDirection>, 2> kWalkDirections = {{
    {WalkDirection::gather, "gather", "adjoint walks from each estimated patch, --walks-per-patch of them"},
    {WalkDirection::shoot, "shoot", "forward particles from the emitters for all patches at once, --particles"},
}};

constexpr bool methods_in_enum_order() {
  for (std::size_t i = 0; i < kWalkMethods.size(); ++i)
    if (static_cast<std::size_t>(kWalkMethods[i].method) != i) return false;
  return true;
}
static_assert(methods_in_enum_order() && in_enum_order(kWalkDirections));

constexpr const WalkMethodRow& method_row(WalkMethod method) { return kWalkMethods[static_cast<std::size_t>(method)]; }
constexpr WalkDirection direction_of(WalkMethod method) { return method_row(method).direction; }
constexpr bool is_gathering(WalkMethod method) { return direction_of(method) == WalkDirection::gather; }
constexpr std::string_view method_name(WalkMethod method) { return method_row(method).name; }
constexpr std::string_view direction_name(WalkDirection direction) { return choice_name(kWalkDirections, direction); }

// Every method, in table order.
std::vector<WalkMethod> all_walk_methods();
// Their names, in table order.
std::vector<std::string> walk_method_names();
// The estimator names of one direction, in table order ("absorption, collision, expected-value").
std::vector<std::string> estimator_names(WalkDirection direction);

// "gather-collision" -> WalkMethod; InputError naming the valid methods (and the nearest) otherwise.
WalkMethod parse_walk_method(std::string_view name);
// "gather" | "shoot"; InputError otherwise.
WalkDirection parse_walk_direction(std::string_view name);
// The method of `estimator` within `direction` (the CLI's --walk and --estimator); InputError naming that
// direction's estimators otherwise ("... is not available for gathering walks").
WalkMethod walk_method(WalkDirection direction, std::string_view estimator);

// The estimator class of method M: specialised next to each estimator (gather_estimators.h, shoot_estimators.h);
// with_estimator (walk_estimators.h) dispatches to it.
template <WalkMethod M>
struct EstimatorOf;

}  // namespace radwalk
