#pragma once
// "Did you mean": the valid choice nearest to a mistyped name, for one-line refusals of unknown names
// (methods, subcommands, options).
//
// Nearness is the optimal-string-alignment distance (Levenshtein plus transposition of adjacent characters,
// each edit costing 1; Damerau 1964), compared without case. A choice is offered only when its distance is at
// most max(1, length of the given name / 3) edits, or when the given name is a prefix of exactly one choice, so
// that 'gather-colision' suggests 'gather-collision' while 'xyz' suggests nothing.
#include <cstddef>
#include <string>
#include <vector>

namespace radwalk {

// Edit distance between a and b (case-insensitive, see above).
std::size_t edit_distance(const std::string& a, const std::string& b);

// The nearest acceptable choice, or "" when none is near enough (ties: the first in `choices`).
std::string nearest_choice(const std::string& given, const std::vector<std::string>& choices);

// " (did you mean 'X'?)" for nearest_choice X, or "" when there is none: ready to append to a message.
std::string did_you_mean(const std::string& given, const std::vector<std::string>& choices);

}  // namespace radwalk
