#pragma once
// Russian-roulette survival of the random walks: the rules, their names, and the one check of their parameter.
//
// A walk at patch k survives with probability p_k, one scalar for all channels; each channel's weight carries
// rho_kc / p_k, so every channel stays unbiased whatever p_k is, as long as
//   p_k < 1 everywhere (walks end), and p_k > 0 wherever some rho_kc > 0 (no path is left out).
// Rules:
//   analog    p_k = the mean of rho_k over channels (exactly rho_k when the channels agree: weights 1),
//   max       p_k = max over channels of rho_k,
//   constant  p_k = c for every patch, c in (0, 1) (Survival::constant).
// The variance depends on the rule (walk_variance.h: finite iff the spectral radius of diag(rho^2 n / p) F < 1).
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "walk/named_choice.h"

namespace radwalk {

enum class SurvivalRule { analog, max, constant };

inline constexpr std::array<NamedChoice<SurvivalRule>, 3> kSurvivalRules = {{
    {SurvivalRule::analog, "analog", "mean rho_k over channels"},
    {SurvivalRule::max, "max", "max rho_k over channels"},
    {SurvivalRule::constant, "constant", "--survival-constant everywhere"},
}};

static_assert(in_enum_order(kSurvivalRules));

constexpr std::string_view survival_name(SurvivalRule rule) { return choice_name(kSurvivalRules, rule); }

// "analog" | "max" | "constant"; InputError naming the valid rules otherwise.
SurvivalRule parse_survival_rule(std::string_view name);

struct Survival {
  SurvivalRule rule = SurvivalRule::analog;
  double constant = 0.5;  // p for SurvivalRule::constant, in (0, 1)
};

// The one check of a survival choice: InputError unless the constant of SurvivalRule::constant is in (0, 1).
void check_survival(const Survival& survival);

// p_k of every patch (check_survival first; throws its InputError).
std::vector<double> survival_probabilities(const PatchRgb& rho, const Survival& survival);

// InputError unless p_k < 1 everywhere and p_k > 0 wherever some rho_kc > 0 (see above); `rule` names the choice
// in the message.
void check_survival_probabilities(const std::vector<double>& p, const PatchRgb& rho, SurvivalRule rule);

}  // namespace radwalk
